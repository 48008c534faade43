#pragma once
// A ship in restricted water (issue 42): squat and the shallow-water resistance from the depth
// under the hull and the ship's particulars, by published empirical methods. The rigid body
// (ship_body.hpp) turns them into loads, so that the hull settles at the published sinkage and
// trim and slows to the published speed by its own dynamics, not as drawn offsets.
//
// Squat (PIANC WG 121 (2014), "Harbour approach channels design guidelines", section on squat;
// Briggs (2009), "Ship squat predictions for ship/tow simulator", ERDC/CHL CHETN-I-72). With the
// depth Froude number Fnh = V / sqrt(g h) and the displaced volume over the length squared,
//   F(Fnh) = Fnh^2 / sqrt(1 - Fnh^2)                       (Tuck 1966: slender-body shallow water)
//   midship sinkage  S_m   = C_z (nabla / Lpp^2) F,  C_z = 1.46       (Tuck 1966, Hooft 1974)
//   maximum squat    S_max = C_s (nabla / Lpp^2) F,  C_s = 2.4        (ICORELS 1980 / PIANC 1980)
//   trim             theta = 2 (S_max - S_m) / Lpp  towards the end that squats most.
// Which end: Barrass (2004, "Ship squat and interaction", Witherby), from model and full-scale
// data: a ship of block coefficient Cb > 0.7 trims by the bow, below 0.7 by the stern, at 0.7 it
// sinks on an even keel. So the squat at that end is ICORELS' S_max and the mean sinkage Tuck's;
// for Cb = 0.7 exactly the trim is zero and the sinkage is S_m.
// Validity (PIANC WG 121 table of methods): ICORELS and Tuck/Hooft for open water and wide
// channels, h/T from 1.1 upwards, Fnh up to about 0.7. Beyond it the linear theory's
// 1 / sqrt(1 - Fnh^2) grows without bound towards the critical speed, which real transcritical
// flow does not do; Fnh is held at 0.7 there (the squat stops growing with speed) and the depth at
// no less than 1.1 T (below that the keel is at the bed, and the seabed contact takes over).
//
// Shallow-water resistance: Lackenby (1963), "The effect of shallow water on ship speed",
// The Shipbuilder and Marine Engine-Builder 70, as the ITTC recommended procedure 7.5-04-01-01.2
// (2014, speed and power trials) gives it: the loss of speed at equal resistance,
//   dV / V_inf = 0.1242 (A_M / h^2 - 0.05) + 1 - sqrt(tanh(g h / V_inf^2)),  A_M / h^2 >= 0.05,
// A_M the midship section area below the waterline (the first term is zero below 0.05, where the
// procedure asks for no correction). A ship whose deep-water resistance is R(V) meets R(V_inf) at
// V = V_inf (1 - dV / V_inf) in depth h: ship_body.cpp evaluates the deep-water drag at that
// equivalent deep-water speed. The same depth clamp (h >= 1.1 T) holds, and dV / V_inf is held
// at no more than 0.6.
namespace nearshore::ships {

/// What squat needs of a ship (particulars_for_hull fills them from the hull at its design draft).
struct SquatParticulars {
  double length_pp_m = 0.0;          ///< Lpp: the waterline length at the design draft
  double draft_m = 0.0;              ///< T
  double block_coefficient = 0.0;    ///< Cb = nabla / (Lpp B T)
  double displaced_volume_m3 = 0.0;  ///< nabla
};

inline constexpr double kTuckSinkageCoefficient = 1.46;   ///< C_z (Tuck 1966, Hooft 1974)
inline constexpr double kIcorelsSquatCoefficient = 2.4;   ///< C_s (ICORELS 1980)
inline constexpr double kBarrassEvenKeelBlockCoefficient = 0.7;
inline constexpr double kSquatMaxDepthFroudeNumber = 0.7;  ///< the methods' upper limit (held beyond)
inline constexpr double kRestrictedWaterMinDepthOverDraft = 1.1;
inline constexpr double kLackenbyMaxSpeedLossFraction = 0.6;

struct Squat {
  double depth_froude_number = 0.0;  ///< V / sqrt(g h) with the clamped depth, before the 0.7 hold
  double midship_sinkage_m = 0.0;    ///< S_m, down > 0
  double trim_rad = 0.0;             ///< bow down > 0 (the ShipState::pitch_rad sign)
  double max_squat_m = 0.0;          ///< S_max at the end that squats most
};

/// Squat of a ship moving at speed_m_s (through the water, either direction: the end that trims
/// down is the same end relative to the motion, so astern the sign of the trim turns) over
/// depth_m (the mean depth under the hull). Zero for a ship without particulars (Lpp or T zero).
Squat squat(const SquatParticulars& ship, double speed_m_s, double depth_m, double gravity_m_s2);

/// Lackenby's dV / V_inf at deep-water speed deep_speed_m_s (see above), held in [0, 0.6].
double lackenby_speed_loss_fraction(double midship_area_m2, double depth_m, double draft_m, double deep_speed_m_s,
                                    double gravity_m_s2);

/// The deep-water speed V_inf whose resistance a ship meets at speed_m_s over depth_m: the root of
/// V_inf (1 - dV / V_inf (V_inf)) = speed_m_s (fixed-point iterations; the tanh term varies slowly).
double deep_water_equivalent_speed_m_s(double midship_area_m2, double depth_m, double draft_m, double speed_m_s,
                                       double gravity_m_s2);

}  // namespace nearshore::ships
