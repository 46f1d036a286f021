#include "surface_legend.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "raster.h"
#include "sfit/render/colormap.h"
#include "text.h"

namespace sfit::render::detail {

namespace {

constexpr Rgb kInk{30, 30, 30};

void draw_title(Image& img, const RenderOptions& o, const Layout& lay) {
  for (std::size_t i = 0; i < o.title.size(); ++i)
    draw_text(img, 8, 4 + static_cast<int>(i) * (lay.line_h + 2) + ascent(), o.title[i], kInk,
              i == 0 ? Weight::kBold : Weight::kRegular);
}

// The colour bar on the right: its scale top to bottom, ticks, and a box for "> T" where a
// point exceeds it.
void draw_bar(Image& img, const RenderOptions& o, const Layout& lay, RenderResult& res) {
  const int W = o.width, lh = lay.line_h;
  const int bx0 = W - lay.bar_w + 14, bx1 = bx0 + 16;
  const int by0 = res.plot_y0 + 2 * lh + 12, by1 = res.plot_y1 - lh;
  res.bar_x0 = bx0;
  res.bar_x1 = bx1;
  res.bar_y0 = by0;
  res.bar_y1 = by1;
  const bool dev = o.mode == Mode::kDeviation;
  for (int y = by0; y < by1; ++y) {
    const double t = 1.0 - (y + 0.5 - by0) / (by1 - by0);  // 1 at the top
    fill_rect(img, bx0, y, bx1, y + 1, dev ? sequential(t) : diverging(2 * t - 1));
  }
  const int tx = bx1 + 5;
  auto tick = [&](double t, const std::string& label) {
    const int y = static_cast<int>(std::lround(by1 - t * (by1 - by0)));
    fill_rect(img, bx1, y, bx1 + 3, y + 1, kInk);
    draw_text(img, tx, y + ascent() / 2 - 1, label, kInk);
  };
  std::string head;
  if (dev) {
    head = "|d| / T";
    tick(0, "0");
    tick(0.5, "0.5 T");
    tick(1, "T");
    if (res.worst_ratio > 1 + 1e-9) {
      fill_rect(img, bx0, by0 - 14, bx1, by0 - 4, kExceeded);
      draw_text(img, tx, by0 - 5, "> T", kInk);
    }
  } else {
    head = o.mode == Mode::kGauss ? "K" : "H";
    tick(1, "+" + format_g(res.scale));
    tick(0.5, "0");
    tick(0, format_g(-res.scale));
  }
  draw_text(img, bx0, res.plot_y0 + lh + 4, head, kInk, Weight::kBold);
}

// The note at the bottom: what the mode shows, in numbers.
std::string note_of(const Scene& sc, const RenderOptions& o, const RenderResult& res) {
  std::string note;
  switch (o.mode) {
    case Mode::kShaded:
      break;
    case Mode::kZebra:
      note = "highlight stripes: " + format_g(o.stripes) +
             " pairs across the surface, light lines " +
             (std::abs(res.stripe_angle) < 0.05
                  ? std::string("vertical")
                  : format_g(res.stripe_angle, 2) + "\xC2\xB0 from vertical");
      break;
    case Mode::kDeviation:
      if (sc.rows && sc.rows->total_points()) {
        const auto& off = sc.rows->offsets();
        const long row =
            static_cast<long>(std::upper_bound(off.begin(), off.end(), res.worst_point) -
                              off.begin()) -
            1;
        note = "max |d|/T " + format_g(res.worst_ratio) + " at row " + std::to_string(row) +
               ", point " + std::to_string(res.worst_point - static_cast<long>(off[row]));
        if (!sc.deviation_note.empty()) note += " (" + sc.deviation_note + ")";
      }
      break;
    case Mode::kGauss:
    case Mode::kMean:
      note = std::string(o.mode == Mode::kGauss ? "K" : "H") + " from " + format_g(res.value_min) +
             " to " + format_g(res.value_max) + "; colours " + "\xC2\xB1" + format_g(res.scale) +
             (o.curvature_scale > 0 ? "" : " (95th percentile of |value|)");
      if (o.mode == Mode::kMean) note += "; normal S_u \xC3\x97 S_v";
      break;
  }
  if (o.exaggeration != 1.0)
    note +=
        (note.empty() ? "" : "; ") + std::string("up axis \xC3\x97 ") + format_g(o.exaggeration);
  return note;
}

}  // namespace

Layout layout_of(const RenderOptions& o) {
  Layout lay;
  lay.has_bar = o.mode == Mode::kDeviation || o.mode == Mode::kGauss || o.mode == Mode::kMean;
  lay.line_h = line_height();
  lay.title_h = o.title.empty() ? 0 : 6 + static_cast<int>(o.title.size()) * (lay.line_h + 2);
  lay.footer_h = o.mode == Mode::kShaded ? 0 : lay.line_h + 8;
  lay.bar_w = lay.has_bar ? 96 : 0;
  return lay;
}

void draw_legend(Image& img, const Scene& sc, const RenderOptions& o, const Layout& lay,
                 double radius, RenderResult& res) {
  if (res.worst_point >= 0) {
    const Eigen::Vector3d q = res.camera.project(sc.rows->points()[res.worst_point]);
    draw_ring(img, q.x(), q.y(), radius + 3.5, 1.6, kInk);
  }
  draw_title(img, o, lay);
  if (lay.has_bar) draw_bar(img, o, lay, res);
  const std::string note = note_of(sc, o, res);
  if (!note.empty()) draw_text(img, 8, o.height - 6, note, kInk);
}

}  // namespace sfit::render::detail
