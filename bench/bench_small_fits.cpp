// The default (FitMethod::kSurface) against the two stages (FitMethod::kSfit01) in process:
// sfit::fit_surface() on every example set at 1e-2, 1e-3 and 1e-4 of its diagonal (closed
// rows as bench/method_ratio.py states them), no process start-up, no reading or writing.
// Speed is measured here, never asserted in tests.
//
//   build/bench/bench_small_fits [--reps N] [--threads T] [--only NAME] [--tol 1e-3]
//                          [--method surface|sfit01]
//
// Prints a Markdown table: counts of both methods, the median wall time of N fits (default 5,
// the two methods alternating) and the ratio default / sfit01, and the same of the process's
// CPU time (less sensitive than the wall time to other work on a shared machine). --only: the sets
// whose name contains NAME; --tol: that relative tolerance alone; --method: run that method alone
// (for perf record), no table.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "sfit/io/rows_reader.h"
#include "sfit/surface_fit.h"

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double cpu_now() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Times {
  double wall, cpu;
};

Times seconds_of(const sfit::Rows& rows, const sfit::FitOptions& o, sfit::FitResult& r) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_now();
  r = sfit::fit_surface(rows, o);
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
          cpu_now() - c0};
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 5, threads = 1;
  std::string only, method;
  double tol = 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--reps") {
      reps = std::max(1, std::atoi(argv[i + 1]));
    } else if (a == "--threads") {
      threads = std::atoi(argv[i + 1]);
    } else if (a == "--only") {
      only = argv[i + 1];
    } else if (a == "--tol") {
      tol = std::atof(argv[i + 1]);
    } else if (a == "--method") {
      method = argv[i + 1];
    } else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return 2;
    }
  }
  const std::set<std::string> closed_u = {
      "d150_wing.rows",  "iea15mw_blade_af50.rows", "iea3p4mw_blade_ragged9.rows",
      "ring_body.rows",  "bent_tube.rows",          "spout_tube.rows",
      "teapot_body.rows"};
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(SFIT_EXAMPLES_DIR)) {
    const std::string n = e.path().filename().string();
    if (e.path().extension() == ".rows" && n.find(only) != std::string::npos) names.push_back(n);
  }
  std::sort(names.begin(), names.end());
  if (method.empty()) {
    std::printf("In-process fit_surface(), %d thread(s), median of %d, methods alternating.\n\n",
                threads, reps);
    std::printf(
        "| data set | points | tolerance | default nu x nv | sfit01 nu x nv | default ms | "
        "sfit01 ms | default / sfit01 | default CPU ms | sfit01 CPU ms | CPU ratio |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n");
  }
  double worst = 0, worst_cpu = 0;
  for (const std::string& name : names) {
    const sfit::Rows rows = sfit::io::read_rows(std::string(SFIT_EXAMPLES_DIR) + "/" + name).rows;
    for (const double rel : {1e-2, 1e-3, 1e-4}) {
      if (tol > 0 && rel != tol) continue;
      sfit::FitOptions o;
      o.tolerance = sfit::relative_tolerance(rows, rel);
      o.closed_u = closed_u.count(name) > 0;
      o.threads = threads;
      sfit::FitOptions o1 = o;
      o1.method = sfit::FitMethod::kSfit01;
      sfit::FitResult r, r1;
      if (!method.empty()) {
        for (int k = 0; k < reps; ++k) seconds_of(rows, method == "sfit01" ? o1 : o, r);
        continue;
      }
      std::vector<double> t, t1, c, c1;
      for (int k = 0; k < reps; ++k) {
        const Times a = seconds_of(rows, o, r), b = seconds_of(rows, o1, r1);
        t.push_back(a.wall);
        c.push_back(a.cpu);
        t1.push_back(b.wall);
        c1.push_back(b.cpu);
      }
      const double a = median(t), b = median(t1), ca = median(c), cb = median(c1);
      worst = std::max(worst, a / b);
      worst_cpu = std::max(worst_cpu, ca / cb);
      std::printf(
          "| %s | %zu | %.0e diag | %dx%d | %dx%d | %.3f | %.3f | %.2f | %.3f | %.3f | %.2f |\n",
          name.c_str(), rows.total_points(), rel, r.surface.count_u, r.surface.count_v,
          r1.surface.count_u, r1.surface.count_v, 1e3 * a, 1e3 * b, a / b, 1e3 * ca, 1e3 * cb,
          ca / cb);
      std::fflush(stdout);
    }
  }
  if (method.empty())
    std::printf("\nLargest ratio default / sfit01: %.2f wall, %.2f CPU (target: at most 1.5)\n",
                worst, worst_cpu);
  return 0;
}
