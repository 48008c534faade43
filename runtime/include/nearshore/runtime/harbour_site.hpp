#pragma once
// Where a baked sequence's harbour sits in the sea and how it fades into the deep water: the
// HarbourSite of surface_snapshot.hpp, read from the sequence folder (manifest.json and depth.exr).
#include "nearshore/runtime/surface_snapshot.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::runtime {

/// The site of `reader`'s sequence:
///  - harbour: depth.exr (reader.read_harbour_grid(verify)); width/height = columns/rows x spacing;
///  - the wave maker's side from the manifest's deep_water.coupling.blending record (axis, side,
///    source_line_m, start_m, width_m). Without one (no [deep_water] that drives the maker) the
///    south edge is treated like the other three: source_axis 1, inward_sign +1, source_line 0,
///    blend_start 0, blend_width = edge_fade_m;
///  - edge_fade_m: the width over which the three other open edges fade to the deep water. Given
///    (>= 0), it is used as is. Automatic (< 0): the widest sponge layer of the bake on those sides
///    (manifest solver.sponges; inside a sponge the baked waves are damped towards flat water, so
///    the harbour must be faded out over it or its edge shows as a calm band), else the blending
///    width (one peak wavelength: a fade that spans a wave hides the seam as the maker's zone
///    does), else 5 % of the smaller side; never more than a quarter of the smaller side, so the
///    interior keeps its baked waves at full weight;
///  - choppiness: the bake's deep_water.choppiness (1 without one); dry_depth_m: solver.dry_depth_m;
///  - relative_wave_height: relative_wave_height(reader, site) below.
/// Throws nearshore::Error naming depth.exr or the manifest if either is unreadable.
HarbourSite read_harbour_site(const sequence::SequenceReader& reader, double edge_fade_m = -1.0,
                              sequence::Verify verify = sequence::Verify::kNo);

/// Frames relative_wave_height reads, evenly spread over the sequence: about one every 10-20
/// wave periods in a 10-minute bake, so the samples are independent and Hs = 4 sqrt(m0) of each
/// cell carries a sampling error of sqrt(1 / (2 n)) = 10 % (the [1 2 1] smoothing lowers it).
inline constexpr int kRelativeWaveHeightFrames = 48;

/// Hs(cell) / Hs(incident) of the sequence's surface elevation (HarbourSite::relative_wave_height):
/// Hs = 4 sqrt(m0) (core/elevation_moments.hpp) over up to kRelativeWaveHeightFrames frames
/// spread evenly over the sequence, smoothed by [1 2 1] x [1 2 1] over the water cells; the
/// incident Hs is the median Hs of the water cells on the line where the baked weight first
/// reaches 1 (site.blend_start_m + blend_width_m inland of the source line: the sea the bake
/// carries in from its wave maker). Empty for fewer than 8 readable frames or no incident sea
/// (Hs below 1 mm); frames that fail to decode are skipped (the streaming engine reports them
/// when it plays them).
Raster<float> relative_wave_height(const sequence::SequenceReader& reader, const HarbourSite& site);

}  // namespace nearshore::runtime
