#include "rownav/io/mesh_reader.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>

namespace rownav::io {

sim::TriangleMesh read_mesh(const std::filesystem::path& file, sim::SurfaceClass label) {
  const std::string name = file.string();
  if (!std::filesystem::is_regular_file(file)) throw InputError(name, "", "no such file");
  Assimp::Importer importer;
  // Pre-transforming bakes the node hierarchy (DAE / OBJ groups) into world-frame vertices.
  const aiScene* scene =
      importer.ReadFile(name, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices);
  if (scene == nullptr)
    throw InputError(name, "", std::string("unreadable mesh: ") + importer.GetErrorString());
  sim::TriangleMesh out;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      out.add_vertex(Eigen::Vector3f(p.x, p.y, p.z));
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      out.add_triangle(base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2],
                       label);
    }
  }
  if (out.empty()) throw InputError(name, "", "mesh has no triangles");
  return out;
}

}  // namespace rownav::io
