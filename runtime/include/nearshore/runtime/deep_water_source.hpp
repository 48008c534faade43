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
#include <string>
#include <vector>

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

/// The split of an irregular sea between the bake and the deep-water layer (issue 14 item 1;
/// docs/runtime.md "The split"), as the manifest's wave_conditions.spectrum_split records it: the
/// bake made the components up to its band's top, the rest were left to the FFT layer, which the
/// runtime draws everywhere, inside the harbour rectangle too, on top of the bake's frames.
struct SpectrumSplitRecord {
  /// The field's waves above this frequency (Hz) are the deep-water layer's: the edge between the
  /// bake's highest frequency cell and the lowest left one, or, when the field drove the wave
  /// maker, the highest frequency the maker made (bake_case.cpp). Older manifests without
  /// split_frequency_hz: bake_max_frequency_hz.
  double split_frequency_hz = 0.0;
  double bake_min_frequency_hz = 0.0, bake_max_frequency_hz = 0.0;  ///< the bake's components' range (Hz)
  double bake_significant_wave_height_m = 0.0;        ///< 4 sqrt(sum a^2/2) of the bake's components
  double deep_water_significant_wave_height_m = 0.0;  ///< the same of the components left to the layer
  double total_significant_wave_height_m = 0.0;       ///< Hs_total^2 = Hs_bake^2 + Hs_deep^2
  bool deep_water_layer_present = false;              ///< the bake has a [deep_water] field to draw them
};

/// The manifest's wave_conditions.spectrum_split, or nullopt when the bake split nothing. Throws
/// nearshore::Error naming the manifest's key for a record that is not an object of numbers.
std::optional<SpectrumSplitRecord> read_spectrum_split(const sequence::SequenceManifest& manifest,
                                                       const std::string& manifest_name = "manifest.json");

/// The deep water drawn INSIDE the harbour rectangle, on top of the bake: the field's components
/// above the split frequency, and no other, so no variance is counted twice (the bake holds
/// those below). The field's cascades partition it by |k| (ocean/deep_water.hpp), so most lie
/// wholly on one side of the split: those above are drawn inside as they are (no second FFT);
/// only the one or two that straddle it are synthesised again with their components at or below
/// the split frequency zeroed (same tiles, amplitudes, phases, frequencies: the same waves).
struct DeepWaterInsideLayer {
  double split_angular_frequency_rad_s = 0.0;  ///< components with w above it (rad/s) are drawn inside
  std::uint32_t whole_cascade_mask = 0;        ///< bit c: the field's cascade c lies wholly above
  std::vector<int> straddling_cascades;        ///< the field's cascades that straddle the split
  /// Those cascades with only their components above the split, in the same order (a field of
  /// its own: ocean::DeepWaterField(straddling) synthesises them). Empty when none straddles.
  ocean::RecordedDeepWater straddling;
  int component_count = 0;                     ///< components drawn inside (amplitude > 0)
  double variance_m2 = 0.0;                    ///< sum a^2/2 of them (m^2): Parseval, the layer's spatial variance
  double significant_wave_height_m() const;    ///< 4 sqrt(variance_m2)
  double lowest_angular_frequency_rad_s = 0.0; ///< of the components drawn inside (rad/s)
};

/// The layer of `field` above `split_angular_frequency_rad_s` (rad/s; a component is drawn when
/// w > split (1 + 1e-9), the bake's own round-off guard). Throws nearshore::Error naming the
/// parameter for a split that is not positive and finite.
DeepWaterInsideLayer split_deep_water(const ocean::RecordedDeepWater& field, double split_angular_frequency_rad_s);

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
