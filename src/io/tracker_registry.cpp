#include "rownav/io/tracker_registry.hpp"

#include <yaml-cpp/yaml.h>

#include <functional>
#include <string_view>

#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"
#include "rownav/track/line_ekf.hpp"
#include "rownav/track/model_filter.hpp"
#include "rownav/track/raw_corridor.hpp"
#include "rownav/track/model_matching.hpp"

namespace rownav::io {

namespace {

// Strict decoding of one section `path` of a file, validation errors placed at the key.
template <class T>
void decode_section(const YAML::Node& node, T& out, const std::string& file,
                    const std::string& path) {
  detail::decode_fields(node, out, file, path, {});
  try {
    out.validate();
  } catch (const std::invalid_argument& e) {
    detail::yaml_fail_validation(file, node, path, e.what());
  }
}

using Creator = std::function<std::unique_ptr<track::RowTracker>(
    const YAML::Node&, const std::string&, const std::string&)>;

template <class T, class Config>
Creator creator() {
  return [](const YAML::Node& section, const std::string& file, const std::string& path) {
    Config c;
    decode_section(section, c, file, path);
    return std::unique_ptr<track::RowTracker>(std::make_unique<T>(c));
  };
}

struct Entry {
  std::string_view name;
  Creator make;
};

// Registered trackers: adding one is one line here (and its section in config/track/*.yaml).
const std::vector<Entry>& registry() {
  static const std::vector<Entry> entries = {
      {"model_matching", creator<track::ModelMatchingTracker, track::ModelMatchingConfig>()},
      {"line_ekf", creator<track::LineEkfTracker, track::LineEkfConfig>()},
      {"model_filter", creator<track::ModelFilterTracker, track::ModelFilterConfig>()},
      {"none", creator<track::RawCorridorTracker, track::RawCorridorConfig>()},
  };
  return entries;
}

std::string known_names() {
  std::string out;
  for (const auto& n : tracker_names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

const Entry& find(const std::string& name) {
  for (const auto& e : registry())
    if (e.name == name) return e;
  throw InputError("--tracker", "",
                   "unknown tracker '" + name + "' (known: " + known_names() + ")");
}

}  // namespace

std::vector<std::string> tracker_names() {
  std::vector<std::string> out;
  for (const auto& e : registry()) out.emplace_back(e.name);
  return out;
}

std::unique_ptr<track::RowTracker> make_tracker(const std::string& name,
                                                const std::filesystem::path& config) {
  const Entry& entry = find(name);
  if (config.empty()) return entry.make(YAML::Node(), "", name);
  const std::string file = config.string();
  const YAML::Node root = load_yaml_file(config);
  if (root && !root.IsNull() && !root.IsMap())
    detail::yaml_fail(file, root, "", "expected a map, got " + detail::yaml_describe(root));
  if (root && root.IsMap()) detail::yaml_check_keys(file, root, "", tracker_names(), {});
  const auto section = [&](std::string_view key) {
    return root && root.IsMap() ? root[std::string(key)] : YAML::Node();
  };
  // The other sections are checked too: a typo there is reported even when unused.
  for (const auto& e : registry())
    if (e.name != name && section(e.name)) e.make(section(e.name), file, std::string(e.name));
  return entry.make(section(name), file, name);
}

}  // namespace rownav::io
