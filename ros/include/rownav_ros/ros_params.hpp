#pragma once
/// @file ros_params.hpp Reads ROS parameters into a Config through its `fields` list, so the
/// node never restates a default: a parameter that is not set keeps the Config's value.
#include <ros/node_handle.h>

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "rownav/core/config_fields.hpp"

namespace rownav::ros_bridge {

namespace detail {

template <class T>
struct IsVector : std::false_type {};
template <class T, class A>
struct IsVector<std::vector<T, A>> : std::true_type {};
template <class T>
struct IsConfigVector : std::false_type {};
template <class T, class A>
struct IsConfigVector<std::vector<T, A>> : std::bool_constant<core::HasFields<T>> {};

[[noreturn]] inline void param_fail(const std::string& key, const std::string& reason) {
  throw std::invalid_argument("parameter " + key + ": " + reason);
}

/// A list of numbers given as a string, as `rosrun ... _key:="[0.3, 0, 0.8]"` stores it:
/// "[a, b, c]" or "a, b, c"; nullopt when the text is not such a list.
inline std::optional<std::vector<double>> numbers_from_text(std::string s) {
  for (char& c : s)
    if (c == '[' || c == ']' || c == ',') c = ' ';
  std::istringstream in(s);
  std::vector<double> v;
  std::string item;
  while (in >> item) {
    std::size_t used = 0;
    try {
      v.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      return std::nullopt;
    }
    if (used != item.size()) return std::nullopt;
  }
  return v;
}

/// A list of numbers (a YAML list, or a string holding one).
inline bool get_numbers(const ros::NodeHandle& nh, const std::string& key, std::vector<double>& v) {
  if (nh.getParam(key, v)) return true;
  std::string s;
  if (!nh.getParam(key, s)) return false;
  const auto parsed = numbers_from_text(s);
  if (parsed) v = *parsed;
  return parsed.has_value();
}

/// One parameter into `out`; absent: unchanged.
template <class T>
void read_param(const ros::NodeHandle& nh, const std::string& key, T& out);

template <core::HasFields T>
void read_fields(const ros::NodeHandle& nh, const std::string& ns, T& out) {
  auto visit = [&](std::string_view name, auto& member) {
    read_param(nh, ns.empty() ? std::string(name) : ns + "/" + std::string(name), member);
  };
  T::fields(out, visit);
}

template <class T>
void read_param(const ros::NodeHandle& nh, const std::string& key, T& out) {
  if constexpr (core::HasFields<T>) {
    read_fields(nh, key, out);
  } else if constexpr (IsConfigVector<T>::value) {
    if (nh.hasParam(key)) param_fail(key, "lists of sections are read from the YAML file only");
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    std::vector<double> v;
    if (get_numbers(nh, key, v)) out.assign(v.begin(), v.end());
    else if (nh.hasParam(key)) param_fail(key, "expected a list of numbers");
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    if (!get_numbers(nh, key, out) && nh.hasParam(key))
      param_fail(key, "expected a list of numbers, e.g. [0.3, 0, 0.8, 0, 0, 0]");
  } else if constexpr (IsVector<T>::value) {
    if (!nh.getParam(key, out) && nh.hasParam(key)) param_fail(key, "expected a list");
  } else if constexpr (requires { T::SizeAtCompileTime; }) {  // Eigen fixed-size vector
    std::vector<double> v;
    if (!get_numbers(nh, key, v)) {
      if (nh.hasParam(key)) param_fail(key, "expected a list of numbers");
      return;
    }
    if (v.size() != static_cast<std::size_t>(T::SizeAtCompileTime))
      param_fail(key, "expected " + std::to_string(T::SizeAtCompileTime) + " numbers");
    for (std::size_t i = 0; i < v.size(); ++i)
      out(static_cast<Eigen::Index>(i)) = static_cast<typename T::Scalar>(v[i]);
  } else if constexpr (core::NamedEnum<T>) {
    std::string s;
    if (!nh.getParam(key, s)) {
      if (nh.hasParam(key)) param_fail(key, "expected one of " + core::enum_name_list<T>());
      return;
    }
    if (!core::enum_from_name(std::string_view(s), out))
      param_fail(key, "unknown value '" + s + "' (valid: " + core::enum_name_list<T>() + ")");
  } else if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, double> ||
                       std::is_same_v<T, std::string>) {
    if (!nh.getParam(key, out) && nh.hasParam(key)) param_fail(key, "wrong type");
  } else if constexpr (std::is_floating_point_v<T>) {
    double v = 0.0;
    if (nh.getParam(key, v)) out = static_cast<T>(v);
    else if (nh.hasParam(key)) param_fail(key, "expected a number");
  } else if constexpr (std::is_integral_v<T>) {
    int v = 0;
    if (!nh.getParam(key, v)) {
      if (nh.hasParam(key)) param_fail(key, "expected an integer");
      return;
    }
    if (!std::in_range<T>(v)) param_fail(key, "out of range (got " + std::to_string(v) + ")");
    out = static_cast<T>(v);
  } else {
    static_assert(sizeof(T) == 0, "unsupported Config field type");
  }
}

}  // namespace detail

/// Reads every field of `out` from parameters `ns/<field>` (nested Configs: `ns/<field>/<sub>`)
/// of `nh`, keeping the current value of absent ones, then validates. Throws
/// std::invalid_argument naming the parameter (or the field, for validate()).
template <core::HasFields T>
void read_config(const ros::NodeHandle& nh, const std::string& ns, T& out) {
  detail::read_fields(nh, ns, out);
  try {
    out.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("parameters " + (ns.empty() ? nh.getNamespace() : ns) + ": " +
                                e.what());
  }
}

}  // namespace rownav::ros_bridge
