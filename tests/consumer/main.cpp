// Fits a 3 x 4 sheet with the installed library, and uses each optional component it was
// built with: a picture encoded as PNG (render), a mesh written as STL (exchange).
#include <cstdio>
#include <filesystem>
#include <string>

#include "sfit/io/surface_json.h"
#include "sfit/surface_fit.h"
#include "sfit/version.h"
#ifdef CONSUMER_RENDER
#include "sfit/render/image.h"
#include "sfit/render/surface_picture.h"
#endif
#ifdef CONSUMER_EXCHANGE
#include "sfit/exchange/writers.h"
#endif

int main(int argc, char** argv) {
  sfit::Rows rows;
  for (int j = 0; j < 3; ++j) {
    for (int k = 0; k < 4; ++k) rows.push_point(sfit::Point(k, j, 0.1 * k * j));
    rows.end_row();
  }
  sfit::FitOptions o;
  o.degree_u = o.degree_v = 2;
  o.tolerance = sfit::Point::Constant(1e-6);
  const auto r = sfit::fit_surface(rows, o);
  const std::string json = sfit::io::surface_to_json_text(r.surface, &r.report);
  std::printf("consumer: sfit %s, %d x %d, within tolerance: %s, json %zu bytes\n", sfit::kVersion,
              r.surface.count_u, r.surface.count_v, r.report.within_tolerance ? "yes" : "no",
              json.size());
  bool ok = r.report.within_tolerance && json.size() > 100;
#ifdef CONSUMER_RENDER
  sfit::render::Scene scene;
  scene.surface = &r.surface;
  sfit::render::RenderOptions ro;
  ro.width = 96;
  ro.height = 64;
  const auto png = sfit::render::encode_png(sfit::render::render_surface(scene, ro).image);
  std::printf("consumer: render: png %zu bytes\n", png.size());
  ok = ok && png.size() > 8 && png[1] == 'P' && png[2] == 'N' && png[3] == 'G';
#endif
#ifdef CONSUMER_EXCHANGE
  const std::string stl = std::string(argc > 1 ? argv[1] : ".") + "/consumer.stl";
  sfit::exchange::WriteOptions wo;
  wo.mesh_density = 5;
  sfit::exchange::write_surface(stl, r.surface, wo, &r, &rows);
  const auto size = std::filesystem::file_size(stl);
  std::printf("consumer: exchange: stl %ju bytes\n", static_cast<std::uintmax_t>(size));
  ok = ok && size == 84 + 50 * 2 * 4 * 4;  // binary STL: 5 x 5 samples, 2 x 4 x 4 triangles
#endif
  return ok ? 0 : 1;
}
