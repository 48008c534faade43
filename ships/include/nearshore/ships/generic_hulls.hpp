#pragma once
// Generic hulls made in code, so tests and the demo need no downloads. Each is a closed,
// outward-oriented mesh in the body frame (hull_mesh.hpp) with its origin on the keel at midships
// (x forward, y port, z up), lofted from cross-sections (rings) with flat end caps.
#include <optional>
#include <string>

#include "nearshore/ships/hull_mesh.hpp"

namespace nearshore::ships {

/// A rectangular box barge: length x beam x depth (m), 12 triangles.
HullMesh box_barge(double length_m, double beam_m, double depth_m);

/// The Wigley hull (Wigley 1934; the ITTC's standard test hull) below the waterline z = draft:
///   y(x, z) = (B/2) (1 - (2x/L)^2) (1 - ((draft - z)/draft)^2),  -L/2 <= x <= L/2, 0 <= z <= draft
/// with wall sides continuing the waterline up to depth_m. `sections` stations along x,
/// `levels` points on each side of a section below the waterline.
HullMesh wigley_hull(double length_m, double beam_m, double draft_m, double depth_m, int sections = 41,
                     int levels = 12);

/// A harbour tug (24 m x 9 m x 4.5 m by default): a wide flat bottom with round bilges, a transom
/// stern 85 % of the beam wide, a bow whose waterline closes as a half ellipse over the fore 40 %
/// and whose keel rises forward of 25 % of the length.
HullMesh harbour_tug(double length_m = 24.0, double beam_m = 9.0, double depth_m = 4.5);

/// Main dimensions of a generic hull chosen by name (m); 0 keeps that hull's default.
struct GenericHullDimensions {
  double length_m = 0.0, beam_m = 0.0, depth_m = 0.0;
  double draft_m = 0.0;  ///< the Wigley hull's formula draft
};

/// The generic hulls by the names scenario files and the C API use: "box_barge" (default
/// 20 x 8 x 3 m), "wigley" (20 x 2 m, draft 1.25 m, depth twice the draft), "tug" (24 x 9 x 4.5 m).
/// std::nullopt for any other name (a mesh file); throws nearshore::Error for a negative dimension.
std::optional<HullMesh> generic_hull(const std::string& name, const GenericHullDimensions& dimensions = {});

}  // namespace nearshore::ships
