// Latency of `sfit edit`, server side: from a move request to the response carrying the new
// surface, over HTTP on 127.0.0.1 (the real server, in-process), and the refit alone
// (Session, no HTTP). Drag steps refit at the current counts (quick); a whole move
// (phase once) runs the full count search. Prints p50 and p95 per size.
// Usage: bench_editor [max_points [drag|once]]   (default 100000, both kinds of move)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "api_json.h"
#include "session.h"
#include "sfit/server/editor.h"
#include "synthetic.h"

// After the sfit headers (Eigen): <resolv.h> defines the macro _res.
#include <httplib.h>

using Clock = std::chrono::steady_clock;

namespace {

struct Stats {
  double p50 = 0, p95 = 0;
};
Stats stats(std::vector<double> ms) {
  std::sort(ms.begin(), ms.end());
  auto at = [&](double q) {
    return ms[std::min(ms.size() - 1, static_cast<std::size_t>(q * ms.size()))];
  };
  return {at(0.5), at(0.95)};
}

double since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const long max_points = argc > 1 ? std::atol(argv[1]) : 100000;
  const std::string only = argc > 2 ? argv[2] : "";
  struct Size {
    int rows, per_row;
  };
  std::printf(
      "| points | grid | refit | server refit p50 / p95 ms | HTTP move->surface p50 / p95 ms | n "
      "|\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (const Size sz : {Size{15, 20}, Size{100, 100}, Size{316, 316}}) {
    const long n = static_cast<long>(sz.rows) * sz.per_row;
    if (n > max_points) break;
    const sfit::Rows rows = sfit::bench::grid(sz.rows, sz.per_row);
    sfit::FitOptions o;
    o.tolerance = sfit::relative_tolerance(rows, 1e-3);
    const int reps_quick = n <= 1000 ? 400 : n <= 20000 ? 100 : 20;
    const std::size_t row = sz.rows / 2, index = sz.per_row / 2;
    const sfit::Point p0 = rows[row][index];
    const double step = 1e-3 * sfit::bounding_box(rows).diagonal();

    for (const char* phase : {"drag", "once"}) {
      if (!only.empty() && only != phase) continue;
      // The full search at 10^5 points takes seconds: fewer repetitions.
      const int reps = std::string(phase) == "once" && n > 20000 ? 5 : reps_quick;
      // The refit alone.
      std::vector<double> refit;
      {
        sfit::server::Session s(rows, o);
        const bool drag = std::string(phase) == "drag";
        for (int k = 0; k < reps; ++k) {
          const sfit::Point to = p0 + sfit::Point(0, 0, step * ((k % 7) - 3));
          const auto t0 = Clock::now();
          s.move(row, index, to,
                 drag ? sfit::server::MovePhase::kDrag : sfit::server::MovePhase::kOnce);
          refit.push_back(since(t0));
        }
      }
      // Over HTTP: the request, the refit, the state JSON, the response.
      sfit::server::EditorConfig c;
      c.input = "bench.rows";
      c.rows = rows;
      c.options = o;
      c.token = "bench";
      sfit::server::EditorServer server(std::move(c));
      std::thread t([&] { server.run(); });
      httplib::Client client("127.0.0.1", server.port());
      client.set_keep_alive(true);
      client.set_tcp_nodelay(true);
      client.set_read_timeout(600, 0);  // a full fit of 10^5 points may take many seconds
      const httplib::Headers h{{"X-Sfit-Token", "bench"}};
      std::vector<double> http;
      for (int k = 0; k < reps; ++k) {
        const sfit::Point to = p0 + sfit::Point(0, 0, step * ((k % 7) - 3));
        nlohmann::json body{{"op", "move"},   {"row", row},
                            {"index", index}, {"to", {to.x(), to.y(), to.z()}},
                            {"phase", phase}, {"seq", k}};
        const auto t0 = Clock::now();
        auto r = client.Post("/api/edit?rows=0", h, body.dump(), "application/json");
        http.push_back(since(t0));
        if (!r || r->status != 200) {
          std::fprintf(stderr, "request failed: %s\n",
                       r ? r->body.c_str() : httplib::to_string(r.error()).c_str());
          server.stop();
          t.join();
          return 1;
        }
      }
      server.stop();
      t.join();
      const Stats a = stats(refit), b = stats(http);
      std::printf("| %ld | %d x %d | %s | %.3f / %.3f | %.3f / %.3f | %d |\n", n, sz.rows,
                  sz.per_row, std::string(phase) == "drag" ? "quick (drag)" : "full (once)", a.p50,
                  a.p95, b.p50, b.p95, reps);
      std::fflush(stdout);
    }
  }
  return 0;
}
