#pragma once
// A config-fields visitor that records the field names in order (core/config_fields.hpp).
#include <string>
#include <string_view>
#include <vector>

namespace rownav::test {

struct NameCollector {
  std::vector<std::string> names;
  template <class T>
  void operator()(std::string_view name, T&) {
    names.emplace_back(name);
  }
};

}  // namespace rownav::test
