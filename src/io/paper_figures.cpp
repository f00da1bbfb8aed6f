// Malavazi 2018 Tables 1-3 (004_1bee156ef8a2b3f7.txt) and Bertoglio 2023 Tables I-II
// (003_25dc0df51a1e5faf.txt, simulation), copied from the papers' text.
#include "rownav/io/paper_figures.hpp"

#include <array>
#include <limits>

namespace rownav::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Columns of the paper's tables: RUBY filtered, RUBY only, OPAL filtered, OPAL only, PEARL
// filtered, PEARL only, RANSAC filtered, RANSAC only.
struct Level {
  std::array<double, 8> success, no_crush, ratio;
};
constexpr std::array<Level, 3> kTables = {{
    {{100, 100, 100, 100, 100, 80, 90, 100},
     {100, 100, 100, 100, 100, 80, 90, 100},
     {1.15, 1.38, 1.49, 1.65, 1.33, 3.53, 1.10, 1.09}},
    {{100, 100, 80, 60, 90, 20, 50, 100},
     {100, 100, 70, 50, 90, 10, 20, 100},
     {1.10, 3.75, 2.64, 5.24, 2.10, 7.26, 9.68, 3.27}},
    {{100, 90, 70, 60, 80, 0, 30, 100},
     {100, 100, 70, 50, 80, 0, 0, 100},
     {2.33, 7.20, 3.98, 6.26, 1.41, kNaN, 10.82, 4.51}},
}};

std::optional<int> column(std::string_view detector, bool filtered) {
  constexpr std::array<std::string_view, 4> names = {"ruby", "opal", "pearl", "ransac_lines"};
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == detector) return static_cast<int>(2 * i) + (filtered ? 0 : 1);
  return std::nullopt;
}

}  // namespace

std::optional<MalavaziFigures> malavazi_2018_figures(int level, std::string_view detector,
                                                     bool filtered) {
  const auto col = column(detector, filtered);
  if (!col || level < 1 || level > 3) return std::nullopt;
  const Level& l = kTables[static_cast<std::size_t>(level - 1)];
  const auto c = static_cast<std::size_t>(*col);
  return MalavaziFigures{l.success[c], l.no_crush[c], l.ratio[c]};
}

std::optional<int> weed_level_of(std::string_view field_name) {
  constexpr std::array<std::string_view, 3> suffix = {"_weeds_none", "_weeds_some", "_weeds_many"};
  for (std::size_t i = 0; i < suffix.size(); ++i)
    if (field_name.ends_with(suffix[i])) return static_cast<int>(i) + 1;
  return std::nullopt;
}

std::optional<BertoglioPoleFigures> bertoglio_2023_pole_figures(std::string_view policy) {
  if (policy == "nearest") return BertoglioPoleFigures{0.205, 0.540, 0.038};
  if (policy == "line_fitting") return BertoglioPoleFigures{0.155, 0.363, 0.013};
  return std::nullopt;
}

}  // namespace rownav::io
