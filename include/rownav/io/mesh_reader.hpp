#pragma once
/// @file mesh_reader.hpp Reads triangle meshes (OBJ, STL, DAE, PLY, ... anything assimp reads).
#include <filesystem>

#include "rownav/io/input_error.hpp"
#include "rownav/sim/triangle_mesh.hpp"

namespace rownav::io {

/// Reads every triangle of a mesh file in its own frame and units (node transforms applied),
/// labelling all of them `label`. Polygons are triangulated; points and lines are dropped.
/// @throws InputError when the file is missing, unreadable or holds no triangle
sim::TriangleMesh read_mesh(const std::filesystem::path& file, sim::SurfaceClass label);

}  // namespace rownav::io
