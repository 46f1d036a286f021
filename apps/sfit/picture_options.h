// Picture options shared by 'sfit render' and 'sfit fit --png' (built with sfit_render only).
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "sfit/render/surface_picture.h"
#include "sfit/surface_fit.h"

namespace sfit::cli {

/// The command-line form of render::RenderOptions.
struct PictureArgs {
  std::vector<std::string> modes;  ///< one, or one per picture (fit --png)
  std::string view = "iso";
  std::string up = "z";
  std::string size = "640x480";
  double exaggerate = 1.0;
  bool net = false, points = false, rows = false;
  double stripes = 14;
  double stripe_angle = NAN;  ///< NaN: along the surface's long axis
  double curvature_scale = 0;
  std::string title;
};

/// A number in 4 significant digits; a point as one number when its three are equal.
std::string format_number(double x);
std::string format_point(const Point& p);
/// The file name shown in titles ("standard input" for "-").
std::string display_name(const std::string& path);
/// "WxH" -> (W, H), each min ... 4096; throws Error(kUsage) naming `option`.
std::pair<int, int> parse_picture_size(const std::string& text, const std::string& option, int min);
/// The second title line: what the picture is of (points and rows when `points` > 0, the
/// counts, degrees, closed directions, T when given, the view).
std::string describe_surface(const Surface& s, std::size_t points, std::size_t rows,
                             const Point* tol, const PictureArgs& a);

/// Adds --mode, --view, --up, --size, --exaggerate, --net, --points, --rows, --stripes,
/// --stripe-angle, --curvature-scale, --title to `c` in option group `group`; with `needs` set,
/// each of them requires that option (fit: --png).
void add_picture_options(CLI::App* c, PictureArgs& a, const std::string& group,
                         CLI::Option* needs = nullptr);

/// Checks the picture options and the output paths (extension .png, folder writable) before
/// any work; throws Error(kUsage or kOutputWrite) naming the option or file.
void check_picture_outputs(const std::vector<std::string>& pngs, const PictureArgs& a,
                           const std::string& option);

/// The library options for one picture; throws Error(kUsage) naming the option.
render::RenderOptions picture_options(const PictureArgs& a, render::Mode mode);

/// 'fit --png': one picture per path; modes paired with --mode (one mode applies to all).
/// Deviations are those of the report: at the parameters the fit assigned.
void write_fit_pictures(const std::vector<std::string>& pngs, const PictureArgs& a,
                        const FitResult& fit, const Rows& rows, const std::string& input_name);

}  // namespace sfit::cli
