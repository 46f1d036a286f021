// The STEP/IGES section reader against hostile files: OpenCASCADE runs in a child process, so
// a crash on a one-token edit (a dangling #ref, a DIRECTION where a point belongs, a curve
// trimmed by itself, IGES degree 99) or on random byte edits is a clean one-line error with
// its documented exit code (docs/errors.md), never a crash of sfit; a curve that does not
// translate is refused by name; lengths are read in the file's own unit; closed curves are
// fitted closed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <regex>

#include "section_files.h"
#include "sfit/error.h"
#include "sfit/exchange/readers.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace sfit::exchange {
namespace {

void write_step(const std::string& path, const std::vector<Handle(Geom_Curve)>& curves,
                const char* unit = "MM") {
  ASSERT_TRUE(test::write_section_step(path, test::section_edges(curves), unit)) << path;
}

void write_iges(const std::string& path, const std::vector<Handle(Geom_Curve)>& curves,
                const char* unit = "MM") {
  ASSERT_TRUE(test::write_section_iges(path, curves, unit)) << path;
}

std::string last_line(const std::string& text) {
  std::string t = text;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  const auto nl = t.rfind('\n');
  return nl == std::string::npos ? t : t.substr(nl + 1);
}

// Replaces the first match of `pattern` in `text` (the mutation must apply).
std::string edit(const std::string& text, const std::string& pattern, const std::string& by) {
  const std::regex re(pattern);
  EXPECT_TRUE(std::regex_search(text, re)) << pattern;
  return std::regex_replace(text, re, by, std::regex_constants::format_first_only);
}

// Runs 'sfit fit FILE -o out.json' and checks the documented answer: exit 0 with the output,
// or one of the input codes 3, 4, 5 (or 7) with one error line naming the file and no output.
int fit_expecting_a_clean_answer(const std::string& file, std::string* error = nullptr) {
  const std::string out = fs::path(file).parent_path().string() + "/out.json";
  fs::remove(out);
  const test::Run r =
      test::run_cli("fit " + test::shell_quoted(file) + " -q -o " + test::shell_quoted(out));
  const std::string line = last_line(r.err);
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 3 || r.exit_code == 4 || r.exit_code == 5 ||
              r.exit_code == 7)
      << file << ": exit " << r.exit_code << "\n"
      << r.err;
  if (r.exit_code == 0) {
    EXPECT_TRUE(fs::exists(out)) << file;
  } else {
    EXPECT_EQ(line.rfind("sfit: error: " + file + ": ", 0), 0u) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line only:\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << file;
  }
  if (error) *error = line;
  return r.exit_code;
}

TEST(SectionMutations, OneTokenEditsAreCleanErrors) {
  const std::string dir = test::temp_dir();
  write_step(dir + "/good.step", test::section_curves(1, false, true));
  write_iges(dir + "/good.igs", test::section_curves(1, false, false));
  const std::string step = test::read_file(dir + "/good.step");
  const std::string iges = test::read_file(dir + "/good.igs");
  // The first B-spline curve's control points: #A,#B,...; a DIRECTION's label.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(step, m,
                                std::regex(R"(B_SPLINE_CURVE_WITH_KNOTS\('',3,\((#\d+),(#\d+),)")));
  const std::string first = m[1], second = m[2];
  ASSERT_TRUE(std::regex_search(step, m, std::regex(R"((#\d+) = DIRECTION)")));
  const std::string direction = m[1];
  ASSERT_TRUE(std::regex_search(step, m, std::regex(R"((#\d+) = TRIMMED_CURVE\('',(#\d+),)")));
  const std::string trimmed = m[1], basis = m[2];
  const std::map<std::string, std::string> cases = {
      {"dangling_ref.step",
       edit(step, "\\(" + first + "," + second + ",", "(" + first + ",#99999,")},
      {"direction_as_point.step",
       edit(step, "\\(" + first + "," + second + ",", "(" + first + "," + direction + ",")},
      {"trimmed_by_itself.step", edit(step, trimmed + " = TRIMMED_CURVE\\(''," + basis + ",",
                                      trimmed + " = TRIMMED_CURVE(''," + trimmed + ",")},
      {"degree_99.igs", edit(iges, "\\n126,(\\d+),3,", "\n126,$1,99,")},
  };
  for (const auto& [name, text] : cases) {
    SCOPED_TRACE(name);
    test::write_file(dir + "/" + name, text);
    std::string error;
    const int code = fit_expecting_a_clean_answer(dir + "/" + name, &error);
    // On OpenCASCADE 7.6 each of these crashes the reader: the child's crash is exit 3.
    if (code == 3) {
      EXPECT_EQ(error, "sfit: error: " + dir + "/" + name +
                           ": cannot read the file: OpenCASCADE crashed on it (signal 11, "
                           "Segmentation fault)");
    }
    std::printf("[ measure  ] %s: exit %d: %s\n", name.c_str(), code, error.c_str());
  }
}

TEST(SectionMutations, ACurveThatDoesNotTranslateIsRefusedByName) {
  const std::string dir = test::temp_dir();
  write_step(dir + "/good.step", test::section_curves(1, false, true));
  std::string step = test::read_file(dir + "/good.step");
  std::smatch m;
  ASSERT_TRUE(
      std::regex_search(step, m, std::regex(R"((#\d+) = GEOMETRIC_CURVE_SET\(''\,\((#\d+)\)\);)")));
  const std::string set = m[1], curve = m[2];
  // Knot multiplicities that do not add up: OpenCASCADE cannot make this curve.
  step = edit(step, "\\(4,1,1,1,1,4\\)", "(4,1,1,1,1,1)");
  test::write_file(dir + "/bad_knots.step", step);
  std::string error;
  EXPECT_EQ(fit_expecting_a_clean_answer(dir + "/bad_knots.step", &error), 5);
  EXPECT_EQ(error, "sfit: error: " + dir + "/bad_knots.step: entity " + curve +
                       " (TRIMMED_CURVE) of GEOMETRIC_CURVE_SET " + set +
                       " does not translate to a curve: refusing to fit the other sections "
                       "without it");
}

TEST(SectionMutations, RandomByteEditsNeverCrashSfit) {
  const std::string dir = test::temp_dir();
  write_step(dir + "/good.step", test::section_curves(1, false, false));
  write_iges(dir + "/good.igs", test::section_curves(1, true, false));
  std::mt19937 rng(20261201);
  const std::string alphabet = "0123456789#,.()=-;EDP \n";
  for (const char* ext : {"step", "igs"}) {
    const std::string base = test::read_file(dir + "/good." + ext);
    std::map<int, int> codes;
    for (int i = 0; i < 30; ++i) {
      std::string t = base;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits; ++e) t[rng() % t.size()] = alphabet[rng() % alphabet.size()];
      const std::string file = dir + "/mutant" + std::to_string(i) + "." + ext;
      test::write_file(file, t);
      ++codes[fit_expecting_a_clean_answer(file)];
      fs::remove(file);
    }
    std::string summary;
    for (const auto& [c, n] : codes)
      summary += " exit " + std::to_string(c) + ": " + std::to_string(n);
    std::printf("[ measure  ] 30 random edits of a %s file:%s\n", ext, summary.c_str());
  }
}

TEST(SectionUnits, LengthsAreReadInTheFilesOwnUnit) {
  const std::string dir = test::temp_dir();
  // Curves 12 000 mm long, 12 000 mm apart in the session, written as 12 m.
  write_step(dir + "/metre.step", test::section_curves(12000, false, false), "M");
  write_iges(dir + "/metre.igs", test::section_curves(12000, false, false), "M");
  write_step(dir + "/mm.step", test::section_curves(12000, false, false), "MM");
  for (const std::string f : {"metre.step", "metre.igs", "mm.step"}) {
    SCOPED_TRACE(f);
    const SectionsFile s = read_sections(dir + "/" + f);
    const bool metre = f.rfind("metre", 0) == 0;
    EXPECT_EQ(s.units, metre ? "m" : "mm");
    double largest = 0;
    for (const Point& p : s.rows.points()) largest = std::max(largest, p.cwiseAbs().maxCoeff());
    EXPECT_NEAR(largest, metre ? 24.0 : 24000.0, metre ? 1e-6 : 1e-3);  // the third row at 24 m
  }
  // The CLI says the unit and states it in a STEP output (no --units needed).
  const test::Run r = test::run_cli("fit " + test::shell_quoted(dir + "/metre.step") + " -o " +
                                    test::shell_quoted(dir + "/surface.step"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("sfit: " + dir +
                       "/metre.step: lengths in m (the file's own unit, not "
                       "converted)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(test::read_file(dir + "/surface.step").find("SI_UNIT($,.METRE.)"), std::string::npos);
}

TEST(SectionClosed, ClosedCurvesAreFittedClosedUnlessToldOtherwise) {
  const std::string dir = test::temp_dir();
  write_iges(dir + "/rings.igs", test::section_curves(1, true, false));
  const SectionsFile s = read_sections(dir + "/rings.igs");
  ASSERT_EQ(s.closed.size(), 3u);
  for (bool c : s.closed) EXPECT_TRUE(c);
  test::Run r = test::run_cli("fit " + test::shell_quoted(dir + "/rings.igs") + " -o " +
                              test::shell_quoted(dir + "/a.json"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("note: every section curve in " + dir +
                       "/rings.igs is closed: fitting closed rows (--closed u; give --closed none "
                       "to fit them open)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(test::read_file(dir + "/a.json").find("\"periodic\":[true,false]"), std::string::npos);
  r = test::run_cli("fit " + test::shell_quoted(dir + "/rings.igs") + " --closed none -o " +
                    test::shell_quoted(dir + "/b.json"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: every section curve in " + dir +
                       "/rings.igs is closed, but they are fitted open"),
            std::string::npos)
      << r.err;
  EXPECT_NE(test::read_file(dir + "/b.json").find("\"periodic\":[false,false]"), std::string::npos);
}

}  // namespace
}  // namespace sfit::exchange
