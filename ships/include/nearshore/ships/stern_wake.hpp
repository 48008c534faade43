#pragma once
// The stern wake as foam decals with lifetimes (seed 000 section 4.2.3 (2), eq. 4.29-4.30): each
// time the stern has moved a beam's width since the last decal, a decal is dropped at the stern,
// oriented along the ship's track, with a random texture variant (0-3, the seed's columns); its
// opacity falls linearly with age, alpha = (lifetime - age) / lifetime (the seed's step 4), and its
// width grows as the turbulent wake spreads, width = beam + 2 spread_rate speed age. A renderer
// draws each decal as a quad of width x spacing textured with a foam strip.
#include <cstdint>
#include <deque>
#include <random>
#include <vector>

#include "nearshore/ships/ship_body.hpp"

namespace nearshore::ships {

struct WakeDecal {
  double x_m = 0.0, y_m = 0.0;   ///< centre, site frame
  double yaw_rad = 0.0;          ///< along the track (counter-clockwise from east)
  double width_m = 0.0;          ///< across the track, grows with age
  double length_m = 0.0;         ///< along the track (the drop spacing)
  double age_s = 0.0;
  double lifetime_s = 0.0;
  double intensity = 1.0;        ///< foam at the drop: the propeller's load, |engine order|, at least 0.3
  double spread_m_s = 0.0;       ///< how fast the width grows (m/s)
  int variant = 0;               ///< texture variant 0-3
  double opacity() const { return age_s >= lifetime_s ? 0.0 : intensity * (lifetime_s - age_s) / lifetime_s; }
};

struct SternWakeOptions {
  double lifetime_s = 60.0;
  int max_decals = 128;          ///< the oldest go first beyond this
  double spread_rate = 0.05;     ///< width growth per second per m/s of ship speed (each side)
  double min_speed_m_s = 0.2;    ///< no new decals below this speed
};

class SternWake {
 public:
  explicit SternWake(SternWakeOptions options = {}, std::uint64_t seed = 1);
  /// Ages the decals by dt_s, drops expired ones, and drops a new one at the stern when due.
  void update(const ShipBody& body, double engine_order, double dt_s);
  const std::deque<WakeDecal>& decals() const { return decals_; }

 private:
  SternWakeOptions options_;
  std::mt19937_64 random_;
  std::deque<WakeDecal> decals_;
  bool has_last_ = false;
  double last_x_m_ = 0.0, last_y_m_ = 0.0;
};

/// A point where a ship's wave broke (dispersive_wake.hpp's breaking limit): site frame, and how
/// far its slope passed the limit (|grad eta| / limit - 1).
struct BreakingCrest {
  double x_m = 0.0, y_m = 0.0, excess = 0.0;
};

struct CrestFoamOptions {
  double lifetime_s = 5.0;       ///< a spilling crest's foam patch fades over a few wave periods
  int max_decals = 256;          ///< the oldest go first beyond this
  int max_new_per_update = 32;   ///< the strongest breaking points first
};

/// Foam on breaking crests: a decal (the same WakeDecal a renderer draws for the stern wake) at each
/// point where the ship's wave layer broke, size_m square, along the ship's heading, its intensity
/// 0.3 + 2 excess (at most 1) times the layer's shown weight, fading over the lifetime. A point within
/// half a decal of a decal younger than a quarter of the lifetime adds none (a steady pattern breaks
/// at the same place in the ship's frame every step).
class CrestFoam {
 public:
  explicit CrestFoam(CrestFoamOptions options = {}, std::uint64_t seed = 2);
  void update(const std::vector<BreakingCrest>& crests, double size_m, double yaw_rad, double weight, double dt_s);
  const std::deque<WakeDecal>& decals() const { return decals_; }

 private:
  CrestFoamOptions options_;
  std::mt19937_64 random_;
  std::deque<WakeDecal> decals_;
  std::vector<BreakingCrest> order_;  ///< scratch
};

}  // namespace nearshore::ships
