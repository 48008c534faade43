#include "nearshore/bake/deep_water_tiles.hpp"

#include "nearshore/bake/deep_water_record.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "nearshore/core/error.hpp"
#include "nearshore/core/harbour_grid.hpp"
#include "nearshore/core/progress.hpp"
#include "nearshore/sequence/sequence_writer.hpp"

namespace nearshore::bake {

using namespace nearshore::ocean;  // the deep-water field

TileSetSummary write_deep_water_tile_set(DeepWaterField& field, int cascade, int frames_per_loop,
                                         const std::filesystem::path& folder, const sequence::FrameEncoding& encoding,
                                         int frame_limit) {
  const DeepWaterSpecification& spec = field.specification();
  if (!(spec.loop_period_s > 0.0))
    throw Error(folder.string(), "the deep-water field does not loop, so a baked tile set would not repeat",
                "set a loop period (T_loop > 0 s) in the deep-water specification");
  if (cascade < 0 || cascade >= field.cascade_count())
    throw Error(folder.string(), fmt::format("cascade {} does not exist (the field has {})", cascade, field.cascade_count()),
                fmt::format("give a cascade from 0 to {}", field.cascade_count() - 1));
  if (frames_per_loop < 1)
    throw Error(folder.string(), fmt::format("{} frames per loop", frames_per_loop), "give at least 1 frame per loop");

  const int n = spec.grid_size;
  const double length_m = spec.tile_lengths_m[cascade];
  GridGeometry geometry;
  geometry.columns = n;
  geometry.rows = n;
  geometry.spacing_m = length_m / n;
  geometry.origin_x_m = -0.5 * geometry.spacing_m;  // cell centres on the FFT nodes x = i L / N
  geometry.origin_y_m = -0.5 * geometry.spacing_m;
  const float depth_m = spec.still_water_depth_m > 0.0 ? static_cast<float>(spec.still_water_depth_m) : 1000.0f;
  const HarbourGrid open_water = HarbourGrid::open_water(geometry, depth_m);

  const int frame_count = frame_limit > 0 ? std::min(frame_limit, frames_per_loop) : frames_per_loop;
  sequence::SequenceDescription description;
  description.frame_interval_s = spec.loop_period_s / frames_per_loop;
  description.loop_period_s = frame_count == frames_per_loop ? spec.loop_period_s : 0.0;
  description.seed = spec.seed;
  sequence::DeepWaterSection section = describe_deep_water_field(field);
  section.tile_set_cascade = cascade;
  description.deep_water = std::move(section);
  description.wave_conditions = {{"source", "deep-water FFT field"}, {"spectrum", spec.spectrum->to_json()}};
  description.encoding = encoding;
  sequence::SequenceWriter writer(folder, open_water, description);

  Raster<float> elevation(n, n), flux_x(n, n), flux_y(n, n), breaking(n, n);
  ProgressBar progress("deep-water tiles", frame_count, "frames");
  for (int index = 0; index < frame_count; ++index) {
    field.synthesise(index * description.frame_interval_s, /*with_flux=*/true);
    const DeepWaterFrame& frame = field.frame(cascade);
    // Raster row 0 is the southern row, as the frame's row 0 (y = 0): the layouts agree.
    elevation.values() = frame.surface_elevation_m;
    flux_x.values() = frame.flux_x_m2_s;
    flux_y.values() = frame.flux_y_m2_s;
    for (std::size_t i = 0; i < breaking.size(); ++i)
      breaking.values()[i] = static_cast<float>(
          foam_features(jacobian(frame.displacement_xx[i], frame.displacement_yy[i], frame.displacement_xy[i], spec.choppiness))
              .breaking);
    writer.write_frame(index, {&elevation, &flux_x, &flux_y, &breaking});
    progress.update(index + 1);
  }
  writer.finish(frame_count);
  progress.finish();

  TileSetSummary summary{frame_count, description.frame_interval_s, 0, 0};
  for (int index = 0; index < frame_count; ++index)
    summary.frame_bytes += std::filesystem::file_size(folder / sequence::frame_file_name(index));
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file()) summary.bytes += entry.file_size();
  return summary;
}

}  // namespace nearshore::bake
