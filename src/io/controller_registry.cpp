#include "rownav/io/controller_registry.hpp"

#include <functional>
#include <string_view>

#include "rownav/control/fir_pid.hpp"
#include "rownav/control/lookahead_pid.hpp"
#include "rownav/control/pure_pursuit.hpp"
#include "rownav/control/stanley.hpp"
#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"

namespace rownav::io {

namespace {

// (section, file, section name) -> controller.
using Creator = std::function<std::unique_ptr<control::PathController>(
    const YAML::Node&, const std::string&, const std::string&)>;

// A creator for a controller class C constructed from C::Config; validation errors at the key.
template <class C>
Creator creator() {
  return [](const YAML::Node& section, const std::string& file, const std::string& path) {
    typename C::Config c;
    detail::decode_fields(section, c, file, path, {});
    try {
      c.validate();
    } catch (const std::invalid_argument& e) {
      detail::yaml_fail_validation(file, section, path, e.what());
    }
    return std::unique_ptr<control::PathController>(std::make_unique<C>(c));
  };
}

struct Entry {
  std::string_view name;
  Creator make;
};

// Registered controllers: adding one is one line here (and its section in default.yaml).
const std::vector<Entry>& registry() {
  static const std::vector<Entry> entries = {
      {"stanley", creator<control::StanleyController>()},
      {"lookahead_pid", creator<control::LookaheadPidController>()},
      {"fir_pid", creator<control::FirPidController>()},
      {"pure_pursuit", creator<control::PurePursuitController>()},
  };
  return entries;
}

std::string known_names() {
  std::string out;
  for (const auto& n : controller_names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::vector<std::string> controller_names() {
  std::vector<std::string> out;
  for (const auto& e : registry()) out.emplace_back(e.name);
  return out;
}

std::unique_ptr<control::PathController> make_controller(const std::string& name,
                                                         const std::filesystem::path& config) {
  const Entry* entry = nullptr;
  for (const auto& e : registry())
    if (e.name == name) entry = &e;
  if (entry == nullptr)
    throw InputError("--controller", "",
                     "unknown controller '" + name + "' (known: " + known_names() + ")");
  if (config.empty()) return entry->make(YAML::Node(), "", name);
  const std::string file = config.string();
  const YAML::Node root = load_yaml_file(config);
  if (root && !root.IsNull() && !root.IsMap())
    detail::yaml_fail(file, root, "", "expected a map, got " + detail::yaml_describe(root));
  const bool is_map = root && root.IsMap();
  if (is_map) detail::yaml_check_keys(file, root, "", controller_names(), {});
  const auto section = [&](std::string_view key) {
    return is_map ? root[std::string(key)] : YAML::Node();
  };
  // The other sections are checked too: a typo there is reported even when unused.
  for (const auto& e : registry())
    if (e.name != name && section(e.name)) e.make(section(e.name), file, std::string(e.name));
  return entry->make(section(name), file, name);
}

}  // namespace rownav::io
