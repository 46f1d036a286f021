#include "picture_checks.h"

#include <cmath>
#include <cstdlib>

#include "sfit/render/colormap.h"

namespace sfit::test {

bool is_background(render::Rgb c) {
  return c.r == 255 && c.g == 255 && c.b == 255;
}

std::vector<std::pair<int, int>> interior_pixels(const render::RenderResult& r, int radius) {
  // Summed-area table of the background pixels.
  const render::Image& img = r.image;
  const int W = img.width, H = img.height;
  std::vector<long> sum(static_cast<std::size_t>(W + 1) * (H + 1), 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      sum[(y + 1) * (W + 1) + x + 1] = is_background(img.at(x, y)) + sum[y * (W + 1) + x + 1] +
                                       sum[(y + 1) * (W + 1) + x] - sum[y * (W + 1) + x];
  auto box = [&](int x0, int y0, int x1, int y1) {  // [x0, x1) x [y0, y1)
    return sum[y1 * (W + 1) + x1] - sum[y0 * (W + 1) + x1] - sum[y1 * (W + 1) + x0] +
           sum[y0 * (W + 1) + x0];
  };
  std::vector<std::pair<int, int>> out;
  for (int y = r.plot_y0 + radius; y < r.plot_y1 - radius; ++y)
    for (int x = r.plot_x0 + radius; x < r.plot_x1 - radius; ++x)
      if (box(x - radius, y - radius, x + radius + 1, y + radius + 1) == 0) out.emplace_back(x, y);
  return out;
}

void dump(const render::Image& image, const std::string& name) {
  if (const char* dir = std::getenv("SFIT_RENDER_TEST_DUMP"))
    render::write_png(std::string(dir) + "/" + name + ".png", image);
}

double decode_sequential(render::Rgb c, double* distance) {
  double best = INFINITY, best_t = 0;
  for (int i = 0; i <= 2000; ++i) {
    const double t = i / 2000.0;
    const render::Rgb s = render::sequential(t);
    const double d = std::hypot(double(s.r) - c.r, double(s.g) - c.g, double(s.b) - c.b);
    if (d < best) {
      best = d;
      best_t = t;
    }
  }
  if (distance) *distance = best;
  return best_t;
}

render::RenderOptions small_options(render::Mode mode) {
  render::RenderOptions o;
  o.mode = mode;
  o.width = 320;
  o.height = 240;
  o.supersample = 2;
  return o;
}

FitResult fit_at(const Rows& rows, double tol, bool closed_u, bool closed_v) {
  FitOptions o;
  o.tolerance = Point::Constant(tol);
  o.closed_u = closed_u;
  o.closed_v = closed_v;
  return fit_surface(rows, o);
}

}  // namespace sfit::test
