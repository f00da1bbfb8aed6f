#pragma once
/// @file section_registry.hpp Components chosen by name and configured from one section each of
/// a YAML file (detectors, trackers, controllers): `name: {key: value}` per component, strict
/// keys, errors at the offending key (file:line:col), every section checked even when unused.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rownav/io/input_error.hpp"
#include "rownav/io/yaml_config.hpp"

namespace rownav::io {

/// Strict decoding of one section `path` of `file` into a Config; validation errors are placed at
/// the section.
template <class Config>
void decode_section(const YAML::Node& node, Config& out, const std::string& file,
                    const std::string& path) {
  detail::decode_fields(node, out, file, path, {});
  try {
    out.validate();
  } catch (const std::invalid_argument& e) {
    detail::yaml_fail_validation(file, node, path, e.what());
  }
}

/// A named list of components deriving from Base.
template <class Base>
class SectionRegistry {
 public:
  /// (section node, file, section name) -> component. A null node means every default.
  using Creator = std::function<std::unique_ptr<Base>(const YAML::Node&, const std::string&,
                                                      const std::string&)>;
  struct Entry {
    std::string_view name;
    Creator make;
  };

  /// `option` names the command-line option in errors (--tracker), `kind` the component.
  SectionRegistry(std::string option, std::string kind, std::vector<Entry> entries)
      : option_(std::move(option)), kind_(std::move(kind)), entries_(std::move(entries)) {}

  /// A creator for T constructed from a Config decoded from its section.
  template <class T, class Config = typename T::Config>
  static Creator creator() {
    return [](const YAML::Node& section, const std::string& file, const std::string& path) {
      Config c;
      decode_section(section, c, file, path);
      return std::unique_ptr<Base>(std::make_unique<T>(c));
    };
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.emplace_back(e.name);
    return out;
  }

  /// The entry called `name`; InputError "--option: unknown kind 'x' (known: a, b)" otherwise.
  const Entry& find(const std::string& name) const {
    for (const auto& e : entries_)
      if (e.name == name) return e;
    std::string known;
    for (const auto& e : entries_) known += (known.empty() ? "" : ", ") + std::string(e.name);
    throw InputError(option_, "", "unknown " + kind_ + " '" + name + "' (known: " + known + ")");
  }

  /// Builds `name` from its section of the root map `root` of `file` (null root: defaults),
  /// after checking that every key of the root is a component name or one of `extra_keys`, and
  /// every other component's section too (a typo there is reported even when unused).
  std::unique_ptr<Base> make(const std::string& name, const YAML::Node& root,
                             const std::string& file,
                             const std::vector<std::string>& extra_keys = {}) const {
    const Entry& entry = find(name);
    if (!root || root.IsNull()) return entry.make(YAML::Node(), file, name);
    if (!root.IsMap())
      detail::yaml_fail(file, root, "", "expected a map, got " + detail::yaml_describe(root));
    std::vector<std::string> keys = names();
    keys.insert(keys.end(), extra_keys.begin(), extra_keys.end());
    detail::yaml_check_keys(file, root, "", keys, {});
    for (const auto& e : entries_)
      if (e.name != name && root[std::string(e.name)])
        e.make(root[std::string(e.name)], file, std::string(e.name));
    return entry.make(root[name], file, name);
  }

  /// make() from a config file path (empty: every default).
  std::unique_ptr<Base> make(const std::string& name, const std::filesystem::path& config) const {
    if (config.empty()) return make(name, YAML::Node(), "");
    return make(name, load_yaml_file(config), config.string());
  }

 private:
  std::string option_, kind_;
  std::vector<Entry> entries_;
};

}  // namespace rownav::io
