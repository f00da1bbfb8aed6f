#pragma once
/// @file yaml_config.hpp Strict YAML <-> Config conversion through the Configs' `fields` lists.
///
/// Every key must be a field, every value the field's type; each error is one InputError line
/// `file.yaml:LINE:COL: path.to.key: reason` pointing at the offending node (1-based).
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"
#include "rownav/io/input_error.hpp"

namespace rownav::io {

namespace detail {

/// "line:col" (1-based) of a node, empty when the node has no position.
std::string yaml_position(const YAML::Node& node);
/// Throws InputError "<file>:<line:col>: <path>: <reason>" (reason made single-line).
[[noreturn]] void yaml_fail(const std::string& file, const YAML::Node& node,
                            const std::string& path, const std::string& reason);
/// "a sequence", "a map", "nothing", or the quoted scalar: for "expected X, got Y".
std::string yaml_describe(const YAML::Node& node);
/// Joins a parent path and a key with '.'.
inline std::string join_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}
bool yaml_scalar_double(const std::string& s, double& out);
bool yaml_scalar_bool(const std::string& s, bool& out);
/// Maps a validate() message "a.b[2].c: reason" onto the node of that key (if present) and
/// throws the InputError.
[[noreturn]] void yaml_fail_validation(const std::string& file, const YAML::Node& root,
                                       const std::string& prefix, const std::string& message);
/// Checks `node` is a map whose keys are all in `valid` or `ignore`, without duplicates.
void yaml_check_keys(const std::string& file, const YAML::Node& node, const std::string& path,
                     const std::vector<std::string>& valid, const std::vector<std::string>& ignore);
/// Shortest round-trip text of a double, YAML spelling for inf / nan.
std::string yaml_format_double(double v);

template <class T>
concept EigenFixedVector = requires {
  typename T::Scalar;
  T::RowsAtCompileTime;
  T::ColsAtCompileTime;
}
&&(T::ColsAtCompileTime == 1 || T::RowsAtCompileTime == 1) && (T::SizeAtCompileTime > 0);

template <class T>
struct IsStdVector : std::false_type {};
template <class T, class A>
struct IsStdVector<std::vector<T, A>> : std::true_type {};

struct KeyCollector {
  std::vector<std::string> names;
  template <class T>
  void operator()(std::string_view name, const T&) {
    names.emplace_back(name);
  }
};

template <class T>
void decode_value(const YAML::Node& n, T& out, const std::string& file, const std::string& path);

template <core::HasFields T>
void decode_fields(const YAML::Node& n, T& out, const std::string& file, const std::string& path,
                   const std::vector<std::string>& ignore) {
  if (!n || n.IsNull()) return;  // an empty section keeps every default
  if (!n.IsMap()) yaml_fail(file, n, path, "expected a map, got " + yaml_describe(n));
  KeyCollector keys;
  T::fields(std::as_const(out), keys);
  yaml_check_keys(file, n, path, keys.names, ignore);
  auto visit = [&](std::string_view name, auto& member) {
    const std::string key(name);
    for (const auto& kv : n)
      if (kv.first.Scalar() == key) decode_value(kv.second, member, file, join_path(path, key));
  };
  T::fields(out, visit);
}

template <class T>
void decode_integer(const YAML::Node& n, T& out, const std::string& file, const std::string& path) {
  const std::string& s = n.Scalar();
  std::string_view v(s);
  if (!v.empty() && v.front() == '+') v.remove_prefix(1);
  const bool negative = !v.empty() && v.front() == '-';
  bool ok = false;
  if (negative) {
    long long x = 0;
    const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
    ok = ec == std::errc() && end == v.data() + v.size();
    if (ok && !std::in_range<T>(x))
      yaml_fail(file, n, path,
                "out of range for this field (got " + s +
                    ", must be >= " + std::to_string(std::numeric_limits<T>::min()) + ")");
    out = static_cast<T>(x);
  } else {
    unsigned long long x = 0;
    const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
    ok = (ec == std::errc() || ec == std::errc::result_out_of_range) &&
         end == v.data() + v.size() && !v.empty();
    if (ok && (ec != std::errc() || !std::in_range<T>(x)))
      yaml_fail(file, n, path,
                "out of range for this field (got " + s +
                    ", must be <= " + std::to_string(std::numeric_limits<T>::max()) + ")");
    out = static_cast<T>(x);
  }
  if (!ok) yaml_fail(file, n, path, "expected an integer, got " + yaml_describe(n));
}

template <class T>
void decode_value(const YAML::Node& n, T& out, const std::string& file, const std::string& path) {
  if constexpr (core::HasFields<T>) {
    decode_fields(n, out, file, path, {});
  } else if constexpr (IsStdVector<T>::value || EigenFixedVector<T>) {
    if (!n.IsSequence()) yaml_fail(file, n, path, "expected a list, got " + yaml_describe(n));
    if constexpr (EigenFixedVector<T>) {
      if (n.size() != static_cast<std::size_t>(T::SizeAtCompileTime))
        yaml_fail(file, n, path,
                  "expected a list of " + std::to_string(T::SizeAtCompileTime) + " numbers, got " +
                      std::to_string(n.size()));
      for (std::size_t i = 0; i < n.size(); ++i) {
        typename T::Scalar x{};
        decode_value(n[i], x, file, path + "[" + std::to_string(i) + "]");
        out(static_cast<Eigen::Index>(i)) = x;
      }
    } else {
      T result;
      for (std::size_t i = 0; i < n.size(); ++i) {
        typename T::value_type x{};
        decode_value(n[i], x, file, path + "[" + std::to_string(i) + "]");
        result.push_back(std::move(x));
      }
      out = std::move(result);
    }
  } else {
    if (!n.IsScalar()) yaml_fail(file, n, path, "expected a value, got " + yaml_describe(n));
    if constexpr (std::is_same_v<T, bool>) {
      if (!yaml_scalar_bool(n.Scalar(), out))
        yaml_fail(file, n, path, "expected true or false, got " + yaml_describe(n));
    } else if constexpr (core::NamedEnum<T>) {
      if (!core::enum_from_name(std::string_view(n.Scalar()), out))
        yaml_fail(
            file, n, path,
            "unknown value " + yaml_describe(n) + " (valid: " + core::enum_name_list<T>() + ")");
    } else if constexpr (std::is_integral_v<T>) {
      decode_integer(n, out, file, path);
    } else if constexpr (std::is_floating_point_v<T>) {
      double x = 0.0;
      if (!yaml_scalar_double(n.Scalar(), x))
        yaml_fail(file, n, path, "expected a number, got " + yaml_describe(n));
      if (std::isfinite(x) && !std::isfinite(static_cast<T>(x)))
        yaml_fail(file, n, path, "out of range for this field (got " + n.Scalar() + ")");
      out = static_cast<T>(x);
    } else if constexpr (std::is_same_v<T, std::string>) {
      out = n.Scalar();
    } else {
      static_assert(sizeof(T) == 0, "unsupported Config field type");
    }
  }
}

template <class T>
YAML::Node encode_value(const T& v);

template <core::HasFields T>
YAML::Node encode_fields(const T& c) {
  YAML::Node out(YAML::NodeType::Map);
  auto visit = [&](std::string_view name, const auto& member) {
    out[std::string(name)] = encode_value(member);
  };
  T::fields(c, visit);
  return out;
}

template <class T>
YAML::Node encode_value(const T& v) {
  if constexpr (core::HasFields<T>) {
    return encode_fields(v);
  } else if constexpr (IsStdVector<T>::value || EigenFixedVector<T>) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(v.size()); ++i) {
      if constexpr (EigenFixedVector<T>)
        out.push_back(encode_value(v(i)));
      else
        out.push_back(encode_value(static_cast<typename T::value_type>(v[i])));
    }
    constexpr bool flow = EigenFixedVector<T> || !core::HasFields<typename T::value_type>;
    if (flow) out.SetStyle(YAML::EmitterStyle::Flow);
    return out;
  } else if constexpr (std::is_same_v<T, bool>) {
    return YAML::Node(v ? "true" : "false");
  } else if constexpr (core::NamedEnum<T>) {
    return YAML::Node(std::string(core::enum_name(v)));
  } else if constexpr (std::is_integral_v<T>) {
    return YAML::Node(std::to_string(v));
  } else if constexpr (std::is_same_v<T, float>) {
    std::array<char, 32> buf{};
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    const std::string s(buf.data(), r.ptr);
    return YAML::Node(std::isfinite(v) ? s : yaml_format_double(v));
  } else if constexpr (std::is_floating_point_v<T>) {
    return YAML::Node(yaml_format_double(static_cast<double>(v)));
  } else {
    return YAML::Node(v);
  }
}

}  // namespace detail

/// Strictly decodes `node` into `out`, starting from out's current values (the defaults).
/// Unknown keys, duplicate keys and values of the wrong type or out of the type's range are
/// InputErrors at the offending node's "line:col". Keys in `ignore_keys` are skipped (the
/// caller handles them, e.g. "preset"). A null / empty node keeps every default. Then, when
/// `validate`, calls out.validate() and reports its "field.path: reason" at that key's line:col
/// (no position when the key is not in the file: the default or a combination is at fault).
template <core::HasFields T>
void decode_config(const YAML::Node& node, T& out, const std::string& file,
                   const std::vector<std::string>& ignore_keys = {}, bool validate = true) {
  detail::decode_fields(node, out, file, "", ignore_keys);
  if (!validate) return;
  try {
    out.validate();
  } catch (const std::invalid_argument& e) {
    detail::yaml_fail_validation(file, node, "", e.what());
  }
}

/// Parses a YAML file. Missing / unreadable -> InputError "cannot open"; malformed YAML ->
/// InputError at yaml-cpp's line:col.
YAML::Node load_yaml_file(const std::filesystem::path& file);

/// Loads a YAML file, or only its top-level `key` (absent key: all defaults), into a
/// default-constructed T, strictly (see decode_config), and validates it.
template <core::HasFields T>
T load_config(const std::filesystem::path& file, std::string_view key = {}) {
  const YAML::Node root = load_yaml_file(file);
  const std::string name = file.string();
  T out;
  if (key.empty()) {
    decode_config(root, out, name);
    return out;
  }
  if (root && !root.IsNull() && !root.IsMap())
    detail::yaml_fail(name, root, "", "expected a map, got " + detail::yaml_describe(root));
  const YAML::Node section = root ? root[std::string(key)] : YAML::Node();
  detail::decode_fields(section, out, name, std::string(key), {});
  try {
    out.validate();
  } catch (const std::invalid_argument& e) {
    detail::yaml_fail_validation(name, section, std::string(key), e.what());
  }
  return out;
}

/// Encodes every field (enums by name, doubles in shortest round-trip form): dump defaults,
/// write manifests. decode_config of the result gives back an equal Config.
template <core::HasFields T>
YAML::Node encode_config(const T& c) {
  return detail::encode_fields(c);
}

/// Writes a YAML document; std::runtime_error "<file>: cannot write" on failure.
void save_yaml(const std::filesystem::path& file, const YAML::Node& node);

}  // namespace rownav::io
