// Where the picture is seen from: an orthographic camera given by azimuth and elevation about
// a chosen up axis, fitted to what it must show.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>

#include "sfit/rows.h"

namespace sfit::render {

/// Direction of view. With up axis z: azimuth 0, elevation 0 looks from -y towards +y (front,
/// x to the right); azimuth 90 looks from +x (side, y to the right); elevation 90 looks down
/// (top, x to the right, y up). For up axis y the roles of (x, y, z) go to (z, x, y), for up
/// axis x to (y, z, x), so that "front" always shows the first axis across and the up axis up.
struct View {
  double azimuth = 45.0;      ///< degrees about the up axis
  double elevation = 35.264;  ///< degrees above the horizontal plane (the isometric angle)
  int up_axis = 2;            ///< 0 = x, 1 = y, 2 = z
};

/// "iso", "front", "top", "side" or "AZ,EL" in degrees (EL in -90 ... 90). Throws
/// Error(kUsage) naming `option` for anything else.
View parse_view(const std::string& text, int up_axis, const std::string& option);

/// Orthographic projection of world points to picture pixels.
/// pixel x = origin.x + scale * (p' . right), pixel y = origin.y - scale * (p' . up), depth =
/// p' . toward (larger is nearer), where p' is p with its up coordinate multiplied by
/// `exaggeration`.
struct Camera {
  Eigen::Vector3d right = Eigen::Vector3d::UnitX();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d toward = -Eigen::Vector3d::UnitY();  ///< unit vector from the scene to the eye
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double scale = 1.0;  ///< pixels per (exaggerated) unit
  double exaggeration = 1.0;
  int up_axis = 2;

  /// The camera axes for `view` (origin and scale still to be fitted).
  static Camera looking(const View& view, double exaggeration);
  /// World point to exaggerated world point.
  Point exaggerate(const Point& p) const {
    Point q = p;
    q[up_axis] *= exaggeration;
    return q;
  }
  /// Picture position (x, y) in pixels and depth of a world point.
  Eigen::Vector3d project(const Point& world) const;
  /// Sets origin and scale so that `points` (exaggerated world) fill the rectangle
  /// [x0, x1] x [y0, y1] of the picture, keeping the aspect ratio, with `margin` (fraction).
  void fit(std::span<const Point> points, double x0, double y0, double x1, double y1,
           double margin);
};

}  // namespace sfit::render
