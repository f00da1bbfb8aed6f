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

/// Bertoglio 2023 (003_25dc0df51a1e5faf.txt) Table II, simulation: the pole distance error of
/// one end-point policy during full turns, averaged over three vegetative stages.
struct BertoglioPoleFigures {
  double mean = 0.0, max = 0.0, min = 0.0;  ///< [m]
};

/// Table II's simulation column for policy "nearest" or "line_fitting"; nullopt otherwise.
std::optional<BertoglioPoleFigures> bertoglio_2023_pole_figures(std::string_view policy);

/// Bertoglio 2023 Table I, simulation: mean / max centre displacement [m].
inline constexpr double kBertoglioMeanDisplacement = 0.049, kBertoglioMaxDisplacement = 0.167;

/// Weed level 1-3 of a field named ..._weeds_none / _some / _many; nullopt otherwise.
std::optional<int> weed_level_of(std::string_view field_name);

}  // namespace rownav::io
