// sfit_peers: one tool, one data set, one tolerance per call; prints one JSON object.
//
//   sfit_peers info  --data F.rows
//   sfit_peers fit   --peer sfit|sfit-mt|occt-grid|occt-loft|sisl-grid --data F.rows --tol T
//                    [--closed-u] [--repeats R] [--budget SECONDS] [--check-threads N]
//   sfit_peers check --surface S.json --data F.rows --tol T [--check-threads N]
//   sfit_peers crosscheck --peer P --data F.rows --tol T [--closed-u] [--stride K]
//
// fit times only the tool's fitting call (input conversion and the check are outside), runs it
// up to R times while the total stays under the budget (at least once), and reports the median.
// check reads a surface written by another program (scipy_peer.py) and runs the same checker.
// crosscheck fits once and compares the checker's distance with OpenCASCADE's own
// GeomAPI_ProjectPointOnSurf on every K-th point (a test of the checker, not of the tool).
// bench/peers/run_peers.py drives it; see the README section "Against other tools".
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "checker.h"
#include "peers.h"
#include "sfit/error.h"
#include "sfit/io/rows_reader.h"

namespace {

using sfit::peers::Peer;
using json = nlohmann::json;

std::map<std::string, std::string> parse(int argc, char** argv, int first) {
  std::map<std::string, std::string> o;
  for (int i = first; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0) throw std::runtime_error("unexpected argument " + a);
    if (a == "--closed-u") {
      o[a] = "1";
      continue;
    }
    if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
    o[a] = argv[++i];
  }
  return o;
}

std::string need(const std::map<std::string, std::string>& o, const std::string& key) {
  auto it = o.find(key);
  if (it == o.end()) throw std::runtime_error("missing " + key);
  return it->second;
}

std::string get(const std::map<std::string, std::string>& o, const std::string& key,
                const std::string& fallback) {
  auto it = o.find(key);
  return it == o.end() ? fallback : it->second;
}

json check_json(const Handle(Geom_BSplineSurface) & s, const sfit::Rows& rows, double tol,
                int threads) {
  const auto c = sfit::peers::check_closest(s, rows, tol, threads);
  return {{"max_distance", c.max_distance},
          {"out_of_tolerance", c.out_of_tolerance},
          {"checked_points", c.points},
          {"worst_row", c.worst_row},
          {"worst_index", c.worst_index},
          {"global_searches", c.global_searches},
          {"occt_projections", c.occt_projections},
          {"occt_closer", c.occt_closer}};
}

// A surface in the neutral form scipy_peer.py writes: degrees, full (clamped) knot vectors,
// poles row-major in u (poles[i][j], i along u).
Handle(Geom_BSplineSurface) read_surface(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  const json j = json::parse(in);
  const int du = j.at("degree_u"), dv = j.at("degree_v");
  const auto& poles = j.at("poles");
  const int nu = static_cast<int>(poles.size()), nv = static_cast<int>(poles.at(0).size());
  TColgp_Array2OfPnt p(1, nu, 1, nv);
  for (int a = 0; a < nu; ++a)
    for (int b = 0; b < nv; ++b) {
      const auto& q = poles[a][b];
      p(a + 1, b + 1) = gp_Pnt(q[0], q[1], q[2]);
    }
  auto knots = [](const json& full, TColStd_Array1OfReal& k, TColStd_Array1OfInteger& m) {
    std::vector<double> v;
    std::vector<int> mult;
    for (double t : full) {
      if (!v.empty() && t == v.back()) {
        ++mult.back();
      } else {
        v.push_back(t);
        mult.push_back(1);
      }
    }
    k.Resize(1, static_cast<int>(v.size()), false);
    m.Resize(1, static_cast<int>(v.size()), false);
    for (std::size_t i = 0; i < v.size(); ++i) {
      k(static_cast<int>(i) + 1) = v[i];
      m(static_cast<int>(i) + 1) = mult[i];
    }
  };
  TColStd_Array1OfReal ku(1, 1), kv(1, 1);
  TColStd_Array1OfInteger mu(1, 1), mv(1, 1);
  knots(j.at("knots_u"), ku, mu);
  knots(j.at("knots_v"), kv, mv);
  return new Geom_BSplineSurface(p, ku, kv, mu, mv, du, dv);
}

int run(int argc, char** argv) {
  if (argc < 2) throw std::runtime_error("usage: sfit_peers info|fit|check --data F.rows ...");
  const std::string cmd = argv[1];
  const auto o = parse(argc, argv, 2);
  const sfit::Rows rows = sfit::io::read_rows(need(o, "--data")).rows;
  const int check_threads = std::stoi(get(o, "--check-threads", "2"));
  json out;
  out["points"] = rows.total_points();
  out["rows"] = rows.size();

  if (cmd == "info") {
    const sfit::BoundingBox box = sfit::bounding_box(rows);
    out["diagonal"] = box.diagonal();
    out["grid"] = sfit::peers::is_grid(rows);
    std::size_t lo = rows[0].size(), hi = lo;
    for (std::size_t j = 0; j < rows.size(); ++j) {
      lo = std::min(lo, rows[j].size());
      hi = std::max(hi, rows[j].size());
    }
    out["min_row"] = lo;
    out["max_row"] = hi;
  } else if (cmd == "check") {
    const double tol = std::stod(need(o, "--tol"));
    out["check"] = check_json(read_surface(need(o, "--surface")), rows, tol, check_threads);
  } else if (cmd == "fit" || cmd == "crosscheck") {
    const std::string name = need(o, "--peer");
    const double tol = std::stod(need(o, "--tol"));
    const bool closed_u = o.count("--closed-u") > 0;
    const int repeats = std::stoi(get(o, "--repeats", "5"));
    const double budget = std::stod(get(o, "--budget", "30"));
    std::unique_ptr<Peer> peer;
    if (name == "sfit") {
      peer = sfit::peers::make_sfit(rows, tol, closed_u, 1);
    } else if (name == "sfit-mt") {
      peer = sfit::peers::make_sfit(rows, tol, closed_u, 0);
    } else if (name == "sfit-chord") {
      peer = sfit::peers::make_sfit(rows, tol, closed_u, 1, sfit::Parametrization::kChord);
    } else if (name == "occt-grid") {
      if (!sfit::peers::is_grid(rows)) throw std::runtime_error("occt-grid needs a grid");
      peer = sfit::peers::make_occt_grid(rows, tol);
    } else if (name == "occt-loft") {
      peer = sfit::peers::make_occt_loft(rows, tol, closed_u);
    } else if (name == "sisl-grid") {
      if (!sfit::peers::is_grid(rows)) throw std::runtime_error("sisl-grid needs a grid");
      peer = sfit::peers::make_sisl_grid(rows, tol);
    } else {
      throw std::runtime_error("unknown peer " + name);
    }
    out["peer"] = name;
    out["tolerance"] = tol;
    if (cmd == "crosscheck") {
      peer->fit();
      const Handle(Geom_BSplineSurface) s = peer->surface();
      std::vector<double> mine;
      sfit::peers::check_closest(s, rows, tol, check_threads, &mine);
      const std::size_t stride = std::stoul(get(o, "--stride", "1"));
      double u0, u1, v0, v1;
      s->Bounds(u0, u1, v0, v1);
      GeomAPI_ProjectPointOnSurf projector;
      projector.Init(s, u0, u1, v0, v1);
      std::size_t compared = 0, occt_none = 0, mine_worse = 0, occt_worse = 0;
      double worst_mine = 0, worst_occt = 0;
      const double eps = 1e-9 * sfit::bounding_box(rows).diagonal();
      for (std::size_t i = 0; i < mine.size(); i += stride) {
        const sfit::Point& p = rows.points()[i];
        projector.Perform(gp_Pnt(p.x(), p.y(), p.z()));
        ++compared;
        if (projector.NbPoints() == 0) {
          ++occt_none;
          continue;
        }
        const double d = projector.LowerDistance();
        if (mine[i] > d + eps) ++mine_worse;
        if (d > mine[i] + eps) ++occt_worse;
        worst_mine = std::max(worst_mine, mine[i] - d);
        worst_occt = std::max(worst_occt, d - mine[i]);
      }
      out["compared"] = compared;
      out["occt_found_nothing"] = occt_none;
      out["checker_farther"] = mine_worse;
      out["checker_farther_max"] = worst_mine;
      out["occt_farther"] = occt_worse;
      out["occt_farther_max"] = worst_occt;
      std::cout << out.dump() << "\n";
      return 0;
    }
    std::vector<double> times;
    double total = 0;
    while (times.empty() || (static_cast<int>(times.size()) < repeats && total < budget)) {
      const auto t0 = std::chrono::steady_clock::now();
      peer->fit();
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      times.push_back(s);
      total += s;
    }
    std::vector<double> sorted = times;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    out["times"] = times;
    out["median_s"] = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    out["coefficients"] = peer->coefficients();
    out["shape"] = peer->shape();
    out["notes"] = peer->notes();
    out["check"] = check_json(peer->surface(), rows, tol, check_threads);
  } else {
    throw std::runtime_error("unknown command " + cmd);
  }
  std::cout << out.dump() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const Standard_Failure& f) {
    std::cout << json{{"error", std::string("OCCT: ") + f.GetMessageString()}}.dump() << "\n";
  } catch (const std::exception& e) {
    std::cout << json{{"error", e.what()}}.dump() << "\n";
  }
  return 1;
}
