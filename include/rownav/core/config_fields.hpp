#pragma once
/// @file config_fields.hpp Field reflection for `Config` structs, so that the YAML loader, the ROS
/// node and the config dumper read and write every component's Config without restating defaults.
///
/// A Config lists its fields once more, by name, in a static `fields` function:
/// @code
/// struct VoxelConfig {
///   double voxel_size = 0.15;  ///< [m] voxel edge (Nehme 2021 sec. 4)
///   template <class S, class V> static void fields(S& s, V& v) { v("voxel_size", s.voxel_size); }
///   void validate() const { check_positive(voxel_size, "voxel_size"); }
/// };
/// @endcode
/// `S` is the Config or a const Config, so one list serves reading and writing.
/// Supported field types: bool, integers, float, double, std::string, enums with an
/// `EnumNames` specialisation, std::vector of those, Eigen fixed-size vectors, nested Configs and
/// std::vector of nested Configs.
#include <array>
#include <concepts>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace rownav::core {

/// Names of an enum's values as written in configs. Specialise with
/// `static constexpr std::array<std::pair<E, std::string_view>, N> values{...};`
template <class E>
struct EnumNames;

/// True for enums that have an EnumNames specialisation.
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires { EnumNames<E>::values; };

/// Name of an enum value ("?" if unnamed).
template <NamedEnum E>
constexpr std::string_view enum_name(E e) {
  for (const auto& [value, name] : EnumNames<E>::values)
    if (value == e) return name;
  return "?";
}

/// Parses an enum value by name; false when unknown.
template <NamedEnum E>
constexpr bool enum_from_name(std::string_view s, E& out) {
  for (const auto& [value, name] : EnumNames<E>::values)
    if (name == s) {
      out = value;
      return true;
    }
  return false;
}

/// Comma-separated list of an enum's names, for error messages.
template <NamedEnum E>
std::string enum_name_list() {
  std::string out;
  for (const auto& [value, name] : EnumNames<E>::values) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out;
}

namespace detail {
struct AnyFieldVisitor {
  template <class T>
  void operator()(std::string_view, T&) {}
};
}  // namespace detail

/// True for structs that list their fields with a static `fields(S&, V&)`.
template <class T>
concept HasFields = requires(T& t, detail::AnyFieldVisitor& v) { T::fields(t, v); };

/// Throws std::invalid_argument("<field>: <reason>") when `ok` is false. Used by validate().
inline void check(bool ok, std::string_view field, std::string_view reason) {
  if (!ok) throw std::invalid_argument(std::string(field) + ": " + std::string(reason));
}

namespace detail {
template <class T>
std::string show(const T& v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace detail

/// Field must be > 0.
template <class T>
void check_positive(T value, std::string_view field) {
  check(value > T(0), field, "must be > 0 (got " + detail::show(value) + ")");
}
/// Field must be >= 0.
template <class T>
void check_non_negative(T value, std::string_view field) {
  check(value >= T(0), field, "must be >= 0 (got " + detail::show(value) + ")");
}
/// Field must lie in [lo, hi].
template <class T>
void check_range(T value, T lo, T hi, std::string_view field) {
  check(value >= lo && value <= hi, field,
        "must be in [" + detail::show(lo) + ", " + detail::show(hi) + "] (got " +
            detail::show(value) + ")");
}

/// Runs `validate()` of a nested Config, prefixing its field with `name.` in the message.
template <class C>
void validate_nested(const C& c, std::string_view name) {
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(name) + "." + e.what());
  }
}

}  // namespace rownav::core
