// Section curves from STEP and IGES files of B-spline curves (the lofting workflow): read as
// rows, fitted to a surface within T.
#include <gtest/gtest.h>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_HArray1OfPnt.hxx>

#include <filesystem>

#include "section_files.h"
#include "sfit/error.h"
#include "sfit/exchange/cad_writers.h"
#include "sfit/exchange/readers.h"
#include "sfit/surface_fit.h"
#include "test_support.h"

namespace sfit::exchange {
namespace {

// One B-spline curve through each row: periodic for closed rows (GeomAPI_Interpolate).
std::vector<Handle(Geom_Curve)> curves_through(const Rows& rows, bool closed) {
  std::vector<Handle(Geom_Curve)> out;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const auto row = rows[j];
    Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, static_cast<int>(row.size()));
    for (std::size_t k = 0; k < row.size(); ++k)
      pts->SetValue(static_cast<int>(k) + 1, gp_Pnt(row[k].x(), row[k].y(), row[k].z()));
    GeomAPI_Interpolate interp(pts, closed, 1e-9);
    interp.Perform();
    EXPECT_TRUE(interp.IsDone());
    out.push_back(interp.Curve());
  }
  return out;
}

void write_step_curves(const std::string& path, const std::vector<Handle(Geom_Curve)>& curves) {
  ASSERT_TRUE(test::write_section_step(path, test::section_edges(curves))) << path;
}

void write_iges_curves(const std::string& path, const std::vector<Handle(Geom_Curve)>& curves) {
  ASSERT_TRUE(test::write_section_iges(path, curves)) << path;
}

struct Case {
  const char* file;
  bool closed;
};

class SectionReader : public ::testing::TestWithParam<std::string> {};

void check_sections(const std::string& ext, const Case& c) {
  SCOPED_TRACE(std::string(c.file) + " as " + ext);
  const Rows rows = test::load_rows(test::example(c.file));
  const auto curves = curves_through(rows, c.closed);
  const std::string path = test::temp_dir() + "/sections." + ext;
  if (ext == "step")
    write_step_curves(path, curves);
  else
    write_iges_curves(path, curves);
  ASSERT_TRUE(is_exchange_input(path));
  const SectionsFile f = read_sections(path);
  // One row per curve, in file order, each densely sampled and lying on its curve.
  ASSERT_EQ(f.rows.size(), rows.size());
  EXPECT_TRUE(f.first_line.empty());
  const double diagonal = bounding_box(rows).diagonal();
  for (std::size_t j = 0; j < f.rows.size(); ++j) {
    const auto row = f.rows[j];
    EXPECT_GE(row.size(), static_cast<std::size_t>(kMinSectionSamples));
    EXPECT_GE(row.size(), rows[j].size());
    double off = 0;
    for (const Point& p : row) {
      GeomAPI_ProjectPointOnCurve proj(gp_Pnt(p.x(), p.y(), p.z()), curves[j]);
      off = std::max(off, proj.LowerDistance());
    }
    EXPECT_LE(off, 1e-9 * diagonal) << "row " << j;
    // Starts where the curve starts; a closed curve does not repeat its first point.
    EXPECT_LE((row.front() - rows[j].front()).norm(), 1e-9 * diagonal);
    if (c.closed)
      EXPECT_GT((row.back() - row.front()).norm(), 1e-6 * diagonal);
    else
      EXPECT_LE((row.back() - rows[j].back()).norm(), 1e-9 * diagonal);
  }
  // The lofting workflow: the sampled sections fit within T.
  FitOptions o;
  o.closed_u = c.closed;
  o.tolerance = relative_tolerance(f.rows, 1e-3);
  const FitResult r = fit_surface(f.rows, o);
  EXPECT_TRUE(r.report.within_tolerance);
  for (int a = 0; a < 3; ++a) EXPECT_LE(r.report.max_deviation[a], o.tolerance[a]);
  std::printf(
      "[ measure  ] %s as %s: %zu rows, %zu points, surface %d x %d, max deviation %.3g (T %.3g)\n",
      c.file, ext.c_str(), f.rows.size(), f.rows.total_points(), r.report.count_u, r.report.count_v,
      r.report.max_deviation.maxCoeff(), o.tolerance.x());
}

TEST_P(SectionReader, BSplineSectionCurvesFitWithinTolerance) {
  check_sections(GetParam(), {"d150_wing.rows", true});
  check_sections(GetParam(), {"ship_px121_stations.rows", false});
}

INSTANTIATE_TEST_SUITE_P(Formats, SectionReader, ::testing::Values("step", "iges"));

ErrorCode code_of(const std::string& path, std::string* what = nullptr) {
  try {
    read_sections(path);
  } catch (const Error& e) {
    if (what) *what = e.what();
    return e.code();
  }
  return ErrorCode::kInternal;
}

TEST(SectionReaderErrors, OneClearErrorPerCase) {
  const std::string dir = test::temp_dir();
  std::string what;
  EXPECT_EQ(code_of(dir + "/missing.step", &what), ErrorCode::kInputUnreadable);
  EXPECT_NE(what.find(dir + "/missing.step: "), std::string::npos) << what;
  std::filesystem::create_directories(dir + "/folder.igs");
  EXPECT_EQ(code_of(dir + "/folder.igs"), ErrorCode::kInputUnreadable);
  test::write_file(dir + "/empty.stp", "");
  EXPECT_EQ(code_of(dir + "/empty.stp"), ErrorCode::kInputSyntax);
  test::write_file(dir + "/text.step", "1 2 3\n4 5 6\n");
  EXPECT_EQ(code_of(dir + "/text.step", &what), ErrorCode::kInputSyntax);
  EXPECT_NE(what.find("not a STEP file"), std::string::npos) << what;
  test::write_file(dir + "/text.iges", "hello\n");
  EXPECT_EQ(code_of(dir + "/text.iges"), ErrorCode::kInputSyntax);
  // A file of faces only (our own STEP output) has no section curves.
  Surface s;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.control = {Point(0, 0, 0), Point(0, 1, 0), Point(1, 0, 0), Point(1, 1, 1)};
  write_step(dir + "/face.step", s);
  EXPECT_EQ(code_of(dir + "/face.step", &what), ErrorCode::kInputData);
  EXPECT_NE(what.find("no section curves: the file holds 1 face(s)"), std::string::npos) << what;
  EXPECT_FALSE(is_exchange_input(dir + "/a.rows"));
  EXPECT_TRUE(is_exchange_input(dir + "/A.STP"));
}

}  // namespace
}  // namespace sfit::exchange
