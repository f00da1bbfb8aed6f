#pragma once
/// @file bitmap_font.hpp A built-in 5x7 ASCII bitmap font (with a descender row) for PNG text,
/// so that pictures need no font files. Drawn at integer scales.
#include <cstdint>

namespace rownav::io {

inline constexpr int kGlyphWidth = 5;    ///< [font px] ink columns
inline constexpr int kGlyphRows = 8;     ///< [font px] 7 rows above the baseline + 1 descender
inline constexpr int kGlyphAscent = 7;   ///< [font px] rows above the baseline
inline constexpr int kGlyphAdvance = 6;  ///< [font px] horizontal step between characters

/// Row `row` (0 = top, 7 = descender) of the glyph for `c` as a bit mask, bit 4 = leftmost
/// column. Characters outside ASCII 32..126 draw as '?'.
std::uint8_t glyph_row(char c, int row);

}  // namespace rownav::io
