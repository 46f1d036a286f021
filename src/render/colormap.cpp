#include "sfit/render/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sfit::render {
namespace {

template <std::size_t N>
Rgb interpolate(const std::array<Rgb, N>& anchors, double t) {  // t in [0, 1]
  if (!(t >= 0)) t = 0;                                         // also NaN
  t = std::min(t, 1.0);
  const double x = t * (N - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(x), N - 2);
  const double f = x - static_cast<double>(i);
  auto mix = [f](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + f * (static_cast<double>(b) - a)));
  };
  return {mix(anchors[i].r, anchors[i + 1].r), mix(anchors[i].g, anchors[i + 1].g),
          mix(anchors[i].b, anchors[i + 1].b)};
}

// ColorBrewer YlOrRd (9 classes) at t = 0, 1/8, ..., 1.
constexpr std::array<Rgb, 9> kYlOrRd{{{255, 255, 204},
                                      {255, 237, 160},
                                      {254, 217, 118},
                                      {254, 178, 76},
                                      {253, 141, 60},
                                      {252, 78, 42},
                                      {227, 26, 28},
                                      {189, 0, 38},
                                      {128, 0, 38}}};

// cool-warm at t = -1, -1/2, 0, 1/2, 1.
constexpr std::array<Rgb, 5> kCoolWarm{
    {{59, 76, 192}, {124, 159, 249}, {221, 221, 221}, {244, 154, 123}, {180, 4, 38}}};

}  // namespace

Rgb sequential(double t) {
  return interpolate(kYlOrRd, t);
}

Rgb diverging(double t) {
  if (std::isnan(t)) return kUndefined;
  return interpolate(kCoolWarm, 0.5 * (std::clamp(t, -1.0, 1.0) + 1.0));
}

}  // namespace sfit::render
