// Picture options shared by 'sfit render' and 'sfit fit --png' (built with sfit_render only).
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>
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
