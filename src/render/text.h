// Text on a finished picture, from the embedded DejaVu Sans bitmaps (font_data.inc).
#pragma once

#include <string>
#include <string_view>

#include "sfit/render/image.h"

namespace sfit::render::detail {

enum class Weight { kRegular, kBold };
enum class Align { kLeft, kCentre, kRight };

/// Height of one line of text in pixels.
int line_height(Weight weight = Weight::kRegular);
/// Ascent above the baseline in pixels.
int ascent(Weight weight = Weight::kRegular);
/// Width of `utf8` in pixels; characters outside the embedded set count as '?'.
int text_width(std::string_view utf8, Weight weight = Weight::kRegular);
/// `x` in printf's %g with `digits` significant digits, a leading '-' written as U+2212 (the
/// minus sign of the pictures' labels).
std::string format_g(double x, int digits = 3);
/// Draws `utf8` with its baseline at y, anchored at x by `align`, blending each glyph's
/// coverage over the picture; returns the x just after the text.
int draw_text(Image& image, int x, int baseline, std::string_view utf8, Rgb colour,
              Weight weight = Weight::kRegular, Align align = Align::kLeft);

}  // namespace sfit::render::detail
