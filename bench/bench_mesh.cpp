// The default mesh of fitted examples: choosing the density, tessellating and orienting
// (make_mesh), and the STL write, with the triangle counts and file sizes as counters.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "sfit/exchange/mesh_writers.h"
#include "sfit/exchange/tessellate.h"
#include "sfit/io/rows_reader.h"
#include "sfit/surface_fit.h"

namespace sfit::bench {
namespace {

struct Case {
  const char* file;
  bool closed_u;
};
constexpr Case kCases[] = {{"ship_px121_stations.rows", false},
                           {"d150_wing.rows", true},
                           {"iea3p4mw_blade_ragged9.rows", true},
                           {"table1_synthetic.rows", false}};

const FitResult& fitted(int k) {
  static FitResult fits[std::size(kCases)];
  static bool done[std::size(kCases)] = {};
  if (!done[k]) {
    const Rows rows = io::read_rows(std::string(SFIT_EXAMPLES_DIR) + "/" + kCases[k].file).rows;
    FitOptions o;
    o.closed_u = kCases[k].closed_u;
    o.tolerance = relative_tolerance(rows, 1e-3);
    fits[k] = fit_surface(rows, o);
    done[k] = true;
  }
  return fits[k];
}

void BM_DefaultMesh(benchmark::State& state) {
  const FitResult& f = fitted(static_cast<int>(state.range(0)));
  exchange::Mesh m;
  for (auto _ : state) {
    m = exchange::make_mesh(f.surface, 0, f.report.tolerance.minCoeff(),
                            exchange::NormalRule::kAuto);
    benchmark::DoNotOptimize(m.vertices.data());
  }
  state.SetLabel(kCases[state.range(0)].file);
  state.counters["triangles"] = static_cast<double>(m.triangles.size());
  state.counters["control_points"] = f.surface.count_u * f.surface.count_v;
}
BENCHMARK(BM_DefaultMesh)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

void BM_DefaultStl(benchmark::State& state) {
  const FitResult& f = fitted(static_cast<int>(state.range(0)));
  const std::string path =
      (std::filesystem::temp_directory_path() / "sfit-bench-mesh.stl").string();
  for (auto _ : state)
    exchange::write_stl(path, exchange::make_mesh(f.surface, 0, f.report.tolerance.minCoeff(),
                                                  exchange::NormalRule::kAuto));
  state.SetLabel(kCases[state.range(0)].file);
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  std::filesystem::remove(path);
}
BENCHMARK(BM_DefaultStl)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sfit::bench

BENCHMARK_MAIN();
