#include "rownav/io/field_builder.hpp"

#include <optional>

#include "rownav/io/layout_reader.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/io/mesh_reader.hpp"
#include "rownav/sim/field_zoo.hpp"

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
  options.limits = lc.limits;
  const std::filesystem::path file = resolve(lc.file, base_dir);
  sim::RowLayout layout = read_layout(file, options);
  sim::order_layout_rows(layout);
  // Weeds are scattered over the corridor width: bounded before dressing.
  if (const double spacing = sim::estimate_row_spacing(layout); spacing > lc.limits.max_row_spacing)
    throw InputError(file.string(), "",
                     "layout.limits.max_row_spacing: adjacent rows are " +
                         core::detail::show(spacing) + " m apart (median), more than " +
                         core::detail::show(lc.limits.max_row_spacing) + " m");
  std::optional<sim::TriangleMesh> instance, terrain;
  if (!lc.instance_mesh.empty())
    instance = read_mesh(resolve(lc.instance_mesh, base_dir), sim::SurfaceClass::canopy);
  if (!lc.terrain_mesh.empty()) {
    terrain = read_mesh(resolve(lc.terrain_mesh, base_dir), sim::SurfaceClass::ground);
    sim::transform_mesh(*terrain, lc.terrain_transform);
    sim::label_mesh(*terrain, lc.terrain_labels);
  }
  return sim::dress_layout(layout, config, instance ? &*instance : nullptr,
                           terrain ? &*terrain : nullptr);
}

sim::Field load_field(const std::filesystem::path& file, sim::FieldConfig* config_out) {
  if (const auto ref = sim::parse_zoo_ref(file.string())) {
    const sim::FieldConfig zoo = sim::zoo_field(ref->index, ref->seed);
    if (config_out) *config_out = zoo;
    return build_field(zoo, ".");
  }
  const auto config = load_config<sim::FieldConfig>(file);
  if (config_out) *config_out = config;
  try {
    return build_field(config, file.parent_path());
  } catch (const InputError& e) {
    // A layout / mesh file that is missing, unreadable or empty has no position of its own:
    // point at the field YAML key naming it, so the one-line error says where to fix it.
    if (!e.position().empty()) throw;
    const YAML::Node layout = load_yaml_file(file)["layout"];
    for (const char* key : {"file", "instance_mesh", "terrain_mesh"}) {
      const YAML::Node node = layout ? layout[key] : YAML::Node();
      if (!node || !node.IsScalar()) continue;
      const std::filesystem::path p(node.Scalar());
      if ((p.is_absolute() ? p : file.parent_path() / p).string() != e.file()) continue;
      throw InputError(file.string(), detail::yaml_position(node),
                           std::string("layout.") + key + ": " + e.what());
    }
    throw;
  }
}

}  // namespace rownav::io
