#pragma once
// SequenceWriter: how the baker puts a frame sequence on disk (docs/formats.md, "Baked sequence").
// THIS HEADER IS THE CONTRACT between bake/ (which calls it) and sequence/ (which implements it).
// Frames hold cell-centred fields of the same size as the harbour grid: the solver interpolates its
// face fluxes (staggered grid) to cell centres before calling write_frame.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/raster.hpp"
#include "nearshore/sequence/sequence_format.hpp"

namespace nearshore::sequence {

struct SequenceDescription {
  double frame_interval_s = 0.1;  ///< simulated time between frames
  double first_frame_time_s = 0;  ///< simulated time of frame 0 (after spin-up)
  nlohmann::json wave_conditions; ///< the wave maker as configured (H, T, spectrum, components...)
  std::uint64_t seed = 0;         ///< the phase seed (reproducibility)
  double loop_period_s = 0;       ///< > 0 for a time-periodic bake (exact period), else 0
  std::optional<DeepWaterSection> deep_water;  ///< the deep-water field the bake carries (issue 5), if any
  nlohmann::json solver;          ///< solver parameters, for the record
  FrameEncoding encoding;         ///< compression and half/float per channel (default: measured choice)
};

/// One baked frame: surface elevation eta (m), depth-integrated fluxes P, Q (m^2/s) at cell
/// centres, and a breaking/foam indicator in [0, 1].
struct FrameFields {
  const Raster<float>* surface_elevation_m = nullptr;
  const Raster<float>* flux_x_m2_s = nullptr;
  const Raster<float>* flux_y_m2_s = nullptr;
  const Raster<float>* breaking = nullptr;
};

class SequenceWriter {
 public:
  /// Opens (creating) `folder`; copies the harbour grid beside the frames. With `resume`, frames
  /// already in the folder are kept and later write_frame calls overwrite from their index on.
  SequenceWriter(const std::filesystem::path& folder, const HarbourGrid& harbour, SequenceDescription description,
                 bool resume = false);
  ~SequenceWriter();
  SequenceWriter(const SequenceWriter&) = delete;
  SequenceWriter& operator=(const SequenceWriter&) = delete;

  /// Writes frame `index` (0-based) atomically. Throws nearshore::Error on failure.
  void write_frame(int index, const FrameFields& fields);
  /// Writes the manifest (with checksums) LAST, atomically: only then does the sequence look complete.
  void finish(int frame_count);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nearshore::sequence
