#pragma once
// The range of every fleet parameter, with its reason: one table that ShipFleet::add_ship, the
// orders and the C API (nearshore_fleet_*) check against, so that no value, finite or not, reaches
// physics it would break (issue 44: an initial speed of 1e308 m/s crashed the seabed lookup, 1e8
// m/s hung the bow-wave grid, a 1e-300 kg hull hung it too, a 1e9 m hull allocated 24 GB).
// A value outside its range is refused with a nearshore::Error naming the field, its range, its
// unit and the reason; NaN and infinities are outside every range.
#include <string>

namespace nearshore::ships {

struct ParameterRange {
  double min = 0.0, max = 0.0;  ///< inclusive
  const char* unit = "";
  const char* reason = "";
};

namespace limits {

/// Main dimensions of a hull (generic or from a file). The longest ship ever built (Seawise Giant)
/// was 458 m long, 69 m in beam, with a moulded depth of 30 m; below these minima a hull is no
/// ship the simulator handles (and its pieces fall under a centimetre).
inline constexpr ParameterRange kLength{2.0, 500.0, "m", "ships are 2-500 m long (the longest built: 458 m)"};
inline constexpr ParameterRange kBeam{0.5, 80.0, "m", "ships are 0.5-80 m in beam (the widest built: 69 m)"};
inline constexpr ParameterRange kDepth{0.5, 50.0, "m", "a hull's moulded depth is 0.5-50 m (the deepest built: about 30 m)"};
inline constexpr ParameterRange kDraft{0.05, 35.0, "m",
                                       "a ship's draft is 0.05-35 m (the deepest-laden ships draw about 25 m)"};
/// A displacement given as a mass: the heaviest ship ever afloat (Seawise Giant, laden) displaced
/// 657 000 t, 6.6e8 kg.
inline constexpr ParameterRange kMass{1.0, 1.0e9, "kg", "ships displace up to about 6.6e8 kg (the heaviest afloat: 657 000 t)"};
/// The loading must float the hull at a draft of at least this fraction of its depth: a ship's
/// light displacement is typically 20-40 % of its loaded one, so no ship floats on a film of water;
/// a hull that did (mass_kg = 1e-300) has no wetted area for the bow wave to push.
inline constexpr double kMinDraftFractionOfDepth = 0.05;

/// Speed through the water (initial speed, speed orders), m/s. 30 m/s (58 kn) is above any
/// displacement ship (the fastest container ships and warships make 25-35 kn, 13-18 m/s); the
/// length Froude number is capped at 1 too (max_speed_m_s): above it a hull planes, and this model
/// (hydrostatic pressure, no dynamic lift) is a displacement-ship model.
inline constexpr ParameterRange kSpeed{0.0, 30.0, "m/s",
                                       "a displacement ship sails below 30 m/s (58 kn) and below length Froude "
                                       "number 1 (above it a hull planes, which this model does not represent)"};
inline constexpr double kMaxLengthFroudeNumber = 1.0;

/// Pressure points sampled on a hull. Each costs about 0.6 us a substep at sea (`nearshore bench
/// ships`: 0.53 ms for 896 points) and about 200 bytes; 20 000 points take 12 ms of a 30 Hz frame
/// (two substeps) and 4 MB, so more would not run in real time. Below 100 the pieces are larger
/// than a tenth of a short hull's side and the waterplane is coarse.
inline constexpr ParameterRange kHullPoints{100.0, 20000.0, "points",
                                            "each point costs about 0.6 us a substep and 200 bytes: 20 000 take 12 ms "
                                            "of a 30 Hz frame; fewer than 100 leave the waterplane coarse"};
/// Bow-wave grid size N (N x N cells). A 256^2 step takes about 1.3 ms and a frame 2-4 steps
/// (docs/ships.md, `nearshore bench ships`), so 512^2 takes about 20 ms of a 30 Hz frame on one
/// core and 30 MB; a grid under 16 cells cannot hold its absorbing layers.
inline constexpr ParameterRange kBowWaveCells{16.0, 512.0, "cells",
                                              "a 512 x 512 grid already takes about 20 ms of a 30 Hz frame; fewer than "
                                              "16 cells leave no room for the absorbing layers"};
/// Site coordinates of a ship or a waypoint, m: 1000 km from the harbour grid's corner in any
/// direction (the sea beyond the harbour is endless); double positions there still resolve
/// 1e-10 m, and the bow-wave windows' cell indices stay far inside their integer range.
inline constexpr ParameterRange kSiteCoordinate{-1.0e6, 1.0e6, "m",
                                                "site positions lie within 1000 km of the harbour grid's corner"};

}  // namespace limits

/// The highest speed through the water a ship of length_m may be given or ordered (m/s): 30 m/s,
/// and at most length Froude number 1, sqrt(g L) (limits::kSpeed).
double max_speed_m_s(double length_m, double gravity_m_s2 = 9.81);

/// Throws nearshore::Error(subject, "<field> = <value> is outside [min, max] <unit>: <reason>", fix)
/// unless min <= value <= max (NaN and infinities never are).
void require_in_range(const std::string& subject, const std::string& field, double value, const ParameterRange& range);

/// Formats a value for a message: short, and never a 309-digit number.
std::string format_value(double value);

}  // namespace nearshore::ships
