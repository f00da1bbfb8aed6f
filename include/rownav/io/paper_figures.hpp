#pragma once
/// @file paper_figures.hpp Published figures printed beside rownav's in the bench tables.
#include <optional>
#include <string_view>

namespace rownav::io {

/// One cell of Malavazi 2018 (004_1bee156ef8a2b3f7.txt) Tables 1-3.
struct MalavaziFigures {
  double success = 0.0;           ///< [%] "Success Rate"
  double success_no_crush = 0.0;  ///< [%] "Success rate without crushing plants"
  double ratio_mean = 0.0;        ///< [-] "Average Error" (travelled / 4.8 m; NaN: no success)
};

/// The paper's figures for weed level 1 (none), 2 (some) or 3 (many), detector ruby / opal /
/// pearl / ransac_lines, filtered or not; nullopt for anything else.
std::optional<MalavaziFigures> malavazi_2018_figures(int level, std::string_view detector,
                                                     bool filtered);

/// Weed level 1-3 of a field named ..._weeds_none / _some / _many; nullopt otherwise.
std::optional<int> weed_level_of(std::string_view field_name);

}  // namespace rownav::io
