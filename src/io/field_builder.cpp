#include "rownav/io/field_builder.hpp"

#include <optional>

#include "rownav/io/layout_reader.hpp"
#include "rownav/io/mesh_reader.hpp"

namespace rownav::io {
namespace {

std::filesystem::path resolve(const std::string& path, const std::filesystem::path& base_dir) {
  const std::filesystem::path p(path);
  return p.is_absolute() ? p : base_dir / p;
}

}  // namespace

sim::Field build_field(const sim::FieldConfig& config, const std::filesystem::path& base_dir) {
  config.validate();
  if (config.kind != sim::FieldKind::layout) return sim::generate_field(config);
  const sim::LayoutConfig& lc = config.layout;
  LayoutReadOptions options;
  options.blocks = lc.blocks;
  options.origin_lat_deg = lc.origin_lat_deg;
  options.origin_lon_deg = lc.origin_lon_deg;
  sim::RowLayout layout = read_layout(resolve(lc.file, base_dir), options);
  sim::order_layout_rows(layout);
  std::optional<sim::TriangleMesh> instance, terrain;
  if (!lc.instance_mesh.empty())
    instance = read_mesh(resolve(lc.instance_mesh, base_dir), sim::SurfaceClass::canopy);
  if (!lc.terrain_mesh.empty())
    terrain = read_mesh(resolve(lc.terrain_mesh, base_dir), sim::SurfaceClass::ground);
  return sim::dress_layout(layout, config, instance ? &*instance : nullptr,
                           terrain ? &*terrain : nullptr);
}

}  // namespace rownav::io
