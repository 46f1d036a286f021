#include "text.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <span>

namespace sfit::render::detail {
namespace {

struct GlyphInfo {
  std::uint32_t code;
  int left, top;
  unsigned width, rows;
  long advance;
  std::size_t offset;
};

#include "font_data.inc"

struct Font {
  std::span<const GlyphInfo> glyphs;
  const unsigned char* bits;
  int ascent, line_height;
};

const Font& font(Weight w) {
  static const Font regular{kRegularGlyphs, kRegularBits, kRegularAscent, kRegularLineHeight};
  static const Font bold{kBoldGlyphs, kBoldBits, kBoldAscent, kBoldLineHeight};
  return w == Weight::kBold ? bold : regular;
}

// Decodes one UTF-8 code point at s[i], advancing i; malformed bytes give '?'.
char32_t next_code(std::string_view s, std::size_t& i) {
  const auto b = static_cast<unsigned char>(s[i++]);
  if (b < 0x80) return b;
  int extra = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : -1;
  if (extra < 0) return U'?';
  char32_t c = b & (0x3F >> extra);
  for (int k = 0; k < extra; ++k) {
    if (i >= s.size() || (static_cast<unsigned char>(s[i]) & 0xC0) != 0x80) return U'?';
    c = (c << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
  }
  return c;
}

const GlyphInfo& glyph(const Font& f, char32_t c) {
  if (c >= 32 && c < 127) return f.glyphs[c - 32];
  for (const GlyphInfo& g : f.glyphs)
    if (g.code == c) return g;
  return f.glyphs['?' - 32];
}

}  // namespace

int line_height(Weight w) {
  return font(w).line_height;
}
int ascent(Weight w) {
  return font(w).ascent;
}

int text_width(std::string_view s, Weight w) {
  const Font& f = font(w);
  int x = 0;
  for (std::size_t i = 0; i < s.size();) x += static_cast<int>(glyph(f, next_code(s, i)).advance);
  return x;
}

int draw_text(Image& img, int x, int baseline, std::string_view s, Rgb colour, Weight w,
              Align align) {
  const Font& f = font(w);
  if (align != Align::kLeft) {
    const int width = text_width(s, w);
    x -= align == Align::kCentre ? width / 2 : width;
  }
  for (std::size_t i = 0; i < s.size();) {
    const GlyphInfo& g = glyph(f, next_code(s, i));
    for (unsigned r = 0; r < g.rows; ++r)
      for (unsigned k = 0; k < g.width; ++k) {
        const int px = x + g.left + static_cast<int>(k);
        const int py = baseline - g.top + static_cast<int>(r);
        if (!img.contains(px, py)) continue;
        const double a = f.bits[g.offset + r * g.width + k] / 255.0;
        if (a <= 0) continue;
        const Rgb o = img.at(px, py);
        auto mix = [a](std::uint8_t bg, std::uint8_t fg) {
          return static_cast<std::uint8_t>(bg + a * (static_cast<double>(fg) - bg) + 0.5);
        };
        img.set(px, py, {mix(o.r, colour.r), mix(o.g, colour.g), mix(o.b, colour.b)});
      }
    x += static_cast<int>(g.advance);
  }
  return x;
}

std::string format_g(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  std::string s = buf;
  if (!s.empty() && s[0] == '-') s = "\xE2\x88\x92" + s.substr(1);  // U+2212 minus
  return s;
}

}  // namespace sfit::render::detail
