#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/field_names.hpp"
#include "rownav/core/config_fields.hpp"
#include "rownav/sim/field.hpp"

namespace rownav::core {
namespace {

struct Inner {
  double a = 1.0;  ///< [m]
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("a", s.a);
  }
  void validate() const { check_positive(a, "a"); }
};

struct Outer {
  int n = 3;
  Inner inner;
  template <class S, class V>
  static void fields(S& s, V& v) {
    v("n", s.n);
    v("inner", s.inner);
  }
  void validate() const {
    check_range(n, 1, 10, "n");
    validate_nested(inner, "inner");
  }
};

using test::NameCollector;

TEST(ConfigFields, VisitsFieldsInOrderOnConstAndMutable) {
  static_assert(HasFields<Outer>);
  static_assert(!HasFields<int>);
  NameCollector c;
  const Outer o;
  Outer::fields(o, c);
  EXPECT_EQ(c.names, (std::vector<std::string>{"n", "inner"}));
}

TEST(ConfigFields, ValidateNamesTheNestedField) {
  Outer o;
  o.inner.a = -2.0;
  try {
    o.validate();
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "inner.a: must be > 0 (got -2)");
  }
  o.inner.a = 1.0;
  o.n = 11;
  EXPECT_THROW(o.validate(), std::invalid_argument);
}

TEST(ConfigFields, EnumNamesRoundTrip) {
  sim::FieldKind k{};
  EXPECT_TRUE(enum_from_name("orchard", k));
  EXPECT_EQ(k, sim::FieldKind::orchard);
  EXPECT_EQ(enum_name(sim::FieldKind::row_crop), "row_crop");
  EXPECT_FALSE(enum_from_name("forest", k));
  EXPECT_EQ(enum_name_list<sim::FieldKind>(), "vineyard, orchard, row_crop, layout");
}

}  // namespace
}  // namespace rownav::core
