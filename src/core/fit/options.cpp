// The option table (sfit/options.h): every option of `sfit fit`, once.
#include "sfit/options.h"

#include <cstdio>
#include <mutex>

#include "fit_registry.h"

namespace sfit {

namespace {

std::string g(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

// "a (help a), b or c (help c)": a registry's entries as the option's help lists them.
template <class Entry>
std::string listed(const std::vector<Entry>& entries) {
  std::string out;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    if (k > 0) out += k + 1 < entries.size() ? ", " : entries.size() > 2 ? ", or " : " or ";
    out += entries[k].name;
    if (!entries[k].help.empty()) out += " (" + entries[k].help + ")";
  }
  return out;
}

std::vector<OptionSpec> make_table() {
  using T = OptionType;
  // The allowed methods and parameter rules are the registries' (fit_registry.h); their names
  // are stored where they stay, so the views below do.
  std::vector<std::string_view> method_names, rule_names;
  for (const auto& e : detail::methods()) method_names.push_back(detail::method_name(e.id));
  for (const auto& e : detail::rules()) rule_names.push_back(detail::rule_name(e.id));
  const std::string method_help = listed(detail::methods());
  const std::string rule_help = listed(detail::rules());
  const OptionGroup fit = OptionGroup::kFit, out = OptionGroup::kOutput;
  const double dmin = kMinFitDegree, dmax = kMaxFitDegree;
  return {
      {"degree", "--degree", fit, T::kInteger, "3", dmin, dmax, {}, "degree in both directions"},
      {"degree_u",
       "--degree-u",
       fit,
       T::kInteger,
       "",
       dmin,
       dmax,
       {},
       "degree along the rows (overrides --degree)"},
      {"degree_v",
       "--degree-v",
       fit,
       T::kInteger,
       "",
       dmin,
       dmax,
       {},
       "degree across the rows (overrides --degree)"},
      {"tol",
       "--tol",
       fit,
       T::kTolerance,
       "",
       0,
       0,
       {},
       "tolerance T or Tx,Ty,Tz, absolute, >= 0 (0 interpolates); default " +
           g(kDefaultToleranceFraction) + " of the bounding-box diagonal"},
      {"tol_rel",
       "--tol-rel",
       fit,
       T::kNumber,
       g(kDefaultToleranceFraction),
       0,
       1,
       {},
       "tolerance as a fraction of the bounding-box diagonal (give --tol or --tol-rel)"},
      {"closed",
       "--closed",
       fit,
       T::kChoice,
       "none",
       0,
       0,
       {"u", "v", "uv", "none"},
       "closed directions: u (each row is a closed contour), v (the rows form a closed "
       "sequence), uv (both), none"},
      {"search",
       "--search",
       fit,
       T::kChoice,
       "fast",
       0,
       0,
       {"fast", "linear", "known"},
       "count search: fast, linear (the paper's) or known (the count hints are the answer; "
       "Python and the library only, with row_count_hints and column_count_hints)"},
      {"parameters", "--parameters", fit, T::kChoice, "auto", 0, 0, rule_names,
       "how points get parameters, along and across the rows: " + rule_help},
      {"knots",
       "--knots",
       fit,
       T::kChoice,
       "corners",
       0,
       0,
       {"corners", "uniform", "adaptive"},
       "corners (uniform knots, and where the rows have corners matched across them also a "
       "crease knot at each corner with uniform knots between, on chord parameters remapped to "
       "the corners; kept only when smaller, within T, unfolded and calm between the rows; "
       "open rows), uniform (uniform knots only), or adaptive (uniform knots, and also fits on "
       "knots inserted where the residuals concentrate and removed where not needed; kept only "
       "when smaller, within T and unfolded; along open and closed rows, across open rows "
       "only)"},
      {"method", "--method", fit, T::kChoice, "surface", 0, 0, method_names, method_help},
      {"norm",
       "--norm",
       fit,
       T::kChoice,
       "auto",
       0,
       0,
       {"l2", "linf", "auto"},
       "with --method surface: l2 (least squares), linf (minimax), auto (least squares, "
       "minimax where it misses T by a little)"},
      {"seam",
       "--seam",
       fit,
       T::kChoice,
       "align",
       0,
       0,
       {"align", "keep"},
       "closed rows: align (each row starts where its neighbour starts, same direction) or "
       "keep (as given: the paper's scheme)"},
      {"orient",
       "--orient",
       fit,
       T::kChoice,
       "auto",
       0,
       0,
       {"auto", "keep"},
       "auto (a row running against its neighbour is reversed) or keep"},
      {"fold_guard",
       "--no-fold-guard",
       fit,
       T::kFlag,
       "true",
       0,
       0,
       {},
       "the fold guard: a surface that folds between rows is refitted with other rules across "
       "the rows, then at lower degrees across them (down to 1); --no-fold-guard "
       "(fold_guard=False) keeps "
       "it, at the degree asked for (with --seam keep --orient keep: the paper's scheme "
       "exactly)"},
      {"rerepresent",
       "--rerepresent",
       fit,
       T::kChoice,
       "paper",
       0,
       0,
       {"paper", "arc_length"},
       "where --method sfit01's re-representation samples each row curve: paper or "
       "arc_length (equal arc length, open rows)"},
      {"threads",
       "--threads",
       fit,
       T::kInteger,
       "0",
       0,
       kMaxThreads,
       {},
       "threads, 0: all cores; results do not depend on it"},
      // The files written from the fit.
      {"mesh",
       "--mesh",
       out,
       T::kFlag,
       "false",
       0,
       0,
       {},
       "write .obj as a triangle mesh (what .obj is unless obj_freeform)"},
      {"obj_freeform",
       "--obj-freeform",
       out,
       T::kFlag,
       "false",
       0,
       0,
       {},
       "write .obj as the exact free-form B-spline instead (few viewers show it)"},
      {"mesh_density",
       "--mesh-density",
       out,
       T::kInteger,
       "0",
       kMinMeshDensity,
       kMaxMeshDensity,
       {},
       "tessellation samples per direction, or 0: from the chordal error, within a triangle "
       "budget (docs/meshes.md)"},
      {"normals",
       "--normals",
       out,
       T::kChoice,
       "auto",
       0,
       0,
       {"auto", "flip", "uv"},
       "mesh normals: auto (outward for closed surfaces, up for height fields), flip (the "
       "opposite), uv (as the data runs, S_u x S_v)"},
      {"fields",
       "--fields",
       out,
       T::kFlag,
       "false",
       0,
       0,
       {},
       "add curvature (raw and clipped) and deviation point data (.vtk/.vts)"},
      {"units",
       "--units",
       out,
       T::kChoice,
       "mm",
       0,
       0,
       {"mm", "cm", "m", "km", "um", "in", "ft", "mi"},
       "length unit the STEP/IGES outputs state: mm, cm, m, km, um, in, ft or mi (the CLI's "
       "default: a STEP/IGES input's own unit, else mm); coordinates are written unchanged"},
  };
}

}  // namespace

const std::vector<OptionSpec>& option_table() {
  // Rebuilt when a method or rule is registered or removed (register before fitting: a
  // rebuild moves the entries that references from before point to).
  static std::mutex mutex;
  static long generation = -1;
  static std::vector<OptionSpec> table;
  const std::lock_guard lock(mutex);
  if (const long g = detail::registry_generation(); g != generation) {
    table = make_table();
    generation = g;
  }
  return table;
}

const OptionSpec* find_option(std::string_view name) {
  for (const OptionSpec& s : option_table())
    if (s.name == name) return &s;
  return nullptr;
}

std::string_view to_string(OptionType type) {
  switch (type) {
    case OptionType::kInteger:
      return "integer";
    case OptionType::kNumber:
      return "number";
    case OptionType::kTolerance:
      return "tolerance";
    case OptionType::kChoice:
      return "choice";
    case OptionType::kFlag:
      return "flag";
  }
  return "?";
}

std::string_view to_string(OptionGroup group) {
  return group == OptionGroup::kFit ? "fit" : "output";
}

std::string choice_list(const OptionSpec& spec) {
  std::string out;
  for (std::string_view c : spec.choices) out += (out.empty() ? "" : ", ") + std::string(c);
  return out;
}

std::string full_help(const OptionSpec& s) {
  std::string h = s.help;
  if (s.type == OptionType::kInteger || s.type == OptionType::kNumber)
    h += "; " + g(s.min) + " ... " + g(s.max);
  if (!s.default_value.empty() && s.type != OptionType::kFlag)
    h += " (default " + s.default_value + ")";
  return h;
}

std::string option_table_markdown() {
  std::string md =
      "# The fit options\n\n"
      "Generated from the library's option table (`include/sfit/options.h`) by\n"
      "`sfit options --format markdown` (scripts/cli_doc.sh); a test fails when this file\n"
      "differs from the table. The same table makes `sfit fit`'s flags and help\n"
      "([cli.md](cli.md)), the keywords of the Python module's `sfit.fit()` and `save()`\n"
      "(`sfit.fit_options()` lists them) and the editor's limits (`GET /api/options-table`).\n\n"
      "| keyword | flag | type | default | allowed | what it does |\n"
      "|---|---|---|---|---|---|\n";
  auto cell = [](std::string t) {
    std::string o;
    for (char c : t) o += c == '|' ? std::string("\\|") : std::string(1, c);
    return o;
  };
  for (OptionGroup group : {OptionGroup::kFit, OptionGroup::kOutput}) {
    for (const OptionSpec& s : option_table()) {
      if (s.group != group) continue;
      std::string allowed;
      if (s.type == OptionType::kChoice) allowed = choice_list(s);
      if (s.type == OptionType::kInteger || s.type == OptionType::kNumber)
        allowed = g(s.min) + " ... " + g(s.max);
      if (s.name == "mesh_density") allowed = "0, " + allowed;
      if (s.type == OptionType::kFlag) allowed = "true, false";
      if (s.type == OptionType::kTolerance) allowed = "T or (Tx, Ty, Tz), each >= 0";
      md += "| `" + std::string(s.name) + "` | `" + std::string(s.flag) + "` | " +
            std::string(to_string(s.type)) + " (" + std::string(to_string(s.group)) + ") | " +
            (s.default_value.empty() ? std::string("see text")
                                     : "`" + std::string(s.default_value) + "`") +
            " | " + cell(allowed) + " | " + cell(s.help) + " |\n";
    }
  }
  md +=
      "\nfit: options of the fit (`sfit.fit()`, `sfit.IncrementalFit()`, the editor); output: "
      "options of\nthe files written from it (`Fit.save()`, `Surface.save()`, `sfit "
      "convert`).\n";
  return md;
}

}  // namespace sfit
