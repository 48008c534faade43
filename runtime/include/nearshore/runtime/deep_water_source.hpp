#pragma once
// The deep water beyond the harbour at runtime (docs/runtime.md "Deep water"): either the bake's
// own FFT field (the manifest's deep_water section and its coefficient files, rebuilt exactly:
// the same lattice waves as the harbour's wave maker), or a Beaufort preset when the bake has none.
// And the time mapping that keeps the bake's field phase-coherent with the harbour frames shown.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "nearshore/ocean/deep_water.hpp"
#include "nearshore/runtime/playback_plan.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::runtime {

/// The bake's field as recorded: every cascade of the manifest's deep_water section from its
/// deep_water_cascade_<i>.bin (amplitude, phase, frequency, harmonic; float32 on disk, and when
/// the field loops w = harmonic 2 pi / T_loop exactly in double, as the bake synthesised it), the
/// bands, depth, loop period, choppiness and unresolved slope variance of the section.
/// ocean::DeepWaterField(result) is then the bake's field: the same components with the same
/// phases (tests/runtime: direct sum against the FFT within float tolerance). nullopt when the
/// manifest has no deep_water section or it lists no coefficient files. Throws nearshore::Error
/// naming the file for a missing, truncated or (with Verify::kYes) corrupt coefficient file, or
/// one whose N, L or T_loop disagree with the manifest.
std::optional<ocean::RecordedDeepWater> read_recorded_deep_water(const sequence::SequenceReader& reader,
                                                                 sequence::Verify verify = sequence::Verify::kNo);

/// A Beaufort sea for bakes without [deep_water] (ocean/sea_state_beaufort.hpp, seed 000 table 3.1).
struct BeaufortSea {
  int force = 3;                       ///< 0-12 (0: a flat sea, no field)
  double wind_direction_rad = 0.0;     ///< direction the wind blows towards, counter-clockwise from east
  int grid_size = 128;                 ///< N per cascade (a power of two)
  int cascade_count = 3;
  double shortest_wavelength_m = 0.5;  ///< the last cascade's Nyquist wavelength
  double choppiness = 1.0;             ///< lambda
  std::uint64_t seed = 1;              ///< phases
};

/// The field of `sea`: deep water, no loop (its own continuous time), tiles fitted to the preset's
/// spectrum (ocean::cascade_tile_lengths_for_m). nullptr for force 0. Throws nearshore::Error
/// naming the parameter for a force outside 0-12 or a bad grid size. Takes about 0.1-1 s (the
/// spectrum's cell integrals): build it off the render thread.
std::unique_ptr<ocean::DeepWaterField> build_beaufort_field(const BeaufortSea& sea);

/// Up to four (time, weight) pairs, the bake times whose weighted field is the deep water shown.
struct BakeTimes {
  std::array<ocean::TimedWeight, 4> times{};
  int count = 0;
  std::span<const ocean::TimedWeight> span() const { return {times.data(), static_cast<std::size_t>(count)}; }
};

/// The deep water shown at display time t in plan step k with fraction f (t = (k + f) dt), from
/// the steps k (`now`) and k + 1 (`next`) of the plan. With T(n) = first_frame_time_s + n dt the
/// bake's time of frame n, and D(t) the bake's field at bake time t:
///   D_k(delta) = (1 - w_k) D(T(src_k) + delta) + w_k D(T(tgt_k) + delta)
///   shown      = (1 - f) D_k(f dt) + f D_{k+1}((f - 1) dt)
/// On consecutive steps of one timeline (src_{k+1} = src_k + 1, no blend) both terms are the
/// field at the same bake time T(src_k) + f dt: exactly the field the harbour's wave maker made
/// at that moment (phase-coherent with the frames). Across a jump it crossfades with the same
/// weights as the harbour frames. Equal times are merged and zero weights dropped.
BakeTimes bake_times(const PlanStep& now, const PlanStep& next, double fraction, double frame_interval_s,
                     double first_frame_time_s);

}  // namespace nearshore::runtime
