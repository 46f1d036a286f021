// Reading pictures back for the render tests: which pixels the surface covers, and which
// deviation a colour stands for.
#pragma once

#include <string>
#include <vector>

#include "sfit/render/image.h"
#include "sfit/render/surface_picture.h"
#include "sfit/surface_fit.h"

namespace sfit::test {

/// True where the picture shows the background (pure white).
bool is_background(render::Rgb c);

/// Pixels of the drawing area whose whole (2r+1) x (2r+1) neighbourhood is drawn on: the
/// surface's inside, at least r pixels away from its outline.
std::vector<std::pair<int, int>> interior_pixels(const render::RenderResult& r, int radius = 1);

/// The t in [0, 1] whose sequential() colour is nearest to c, and that distance (RGB units).
double decode_sequential(render::Rgb c, double* distance = nullptr);

/// Writes the picture to $SFIT_RENDER_TEST_DUMP/NAME.png when that variable is set (to look at
/// what a test saw); does nothing otherwise.
void dump(const render::Image& image, const std::string& name);

/// The default fit at T = `tol` on every axis, closed where asked: the surfaces the tests draw.
FitResult fit_at(const Rows& rows, double tol, bool closed_u = false, bool closed_v = false);

/// A small, fast picture: 320 x 240, supersampled 2 x 2, no title.
render::RenderOptions small_options(render::Mode mode);

}  // namespace sfit::test
