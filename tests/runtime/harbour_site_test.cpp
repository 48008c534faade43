// HarbourSite::relative_wave_height (runtime/harbour_site.hpp): the disturbance coefficient
// Hs(cell) / Hs(incident) the renderer shelters the short waves by, from a sequence written by the
// real sequence writer whose wave height is known everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "nearshore/runtime/harbour_site.hpp"
#include "nearshore/sequence/sequence_reader.hpp"
#include "nearshore/sequence/sequence_writer.hpp"
#include "runtime_test_support.hpp"

namespace nearshore::runtime {
namespace {

// A standing oscillation eta = A(x) cos(w t) with A rising linearly from 0.2 m on the west edge to
// 1.0 m on the east one, over open water with a block of land in the north-east: every cell's
// time series has the same shape, so its Hs = 4 sqrt(m0) is A(x) times one factor (the sampled
// cos^2's mean) and K = A(x) / median(A on the incident line) exactly; the [1 2 1] x [1 2 1]
// smoothing keeps a linear A (interior cells; at the land's edge it is renormalised over water).
TEST(HarbourSiteRelativeWaveHeight, IsTheRatioOfEachCellsWaveHeightToTheIncidentSeas) {
  const fs::path folder = testing::scratch_folder();
  const GridGeometry geometry = testing::wave_geometry(40, 30, 5.0);
  HarbourGrid harbour = HarbourGrid::open_water(geometry, 10.f);
  for (int j = 24; j < 30; ++j)
    for (int i = 30; i < 40; ++i) harbour.land(i, j) = 1, harbour.still_water_depth_m(i, j) = -2.f;
  sequence::SequenceDescription description;
  description.frame_interval_s = 0.7;
  description.encoding.surface_elevation = sequence::Precision::kFloat;
  sequence::SequenceWriter writer(folder, harbour, description);
  const auto amplitude_m = [&](int i) { return 0.2 + 0.8 * i / double(geometry.columns - 1); };
  Raster<float> eta(geometry.columns, geometry.rows), zero(geometry.columns, geometry.rows, 0.f);
  const int frames = 60;
  for (int n = 0; n < frames; ++n) {
    const double w = 2.0 * std::numbers::pi / 9.3;  // incommensurate with the frame interval
    for (int j = 0; j < geometry.rows; ++j)
      for (int i = 0; i < geometry.columns; ++i)
        eta(i, j) = harbour.land(i, j) ? 0.f : float(amplitude_m(i) * std::cos(w * n * description.frame_interval_s));
    writer.write_frame(n, {&eta, &zero, &zero, &zero});
  }
  writer.finish(frames);

  const sequence::SequenceReader reader(folder);
  const HarbourSite site = read_harbour_site(reader);
  const Raster<float>& k = site.relative_wave_height;
  ASSERT_EQ(k.columns(), geometry.columns);
  ASSERT_EQ(k.rows(), geometry.rows);
  // The incident line (no wave maker record: edge_fade_m from the south edge) runs through open
  // water only: its median amplitude is the middle of the 40 columns' (columns 19 and 20: the
  // upper one).
  const double incident_amplitude_m = amplitude_m(20);
  for (int j = 1; j + 1 < geometry.rows; ++j)
    for (int i = 1; i + 1 < geometry.columns; ++i) {
      if (harbour.land(i, j)) {
        EXPECT_TRUE(std::isnan(k(i, j))) << "land cell (" << i << ", " << j << ")";
        continue;
      }
      bool beside_land = false;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) beside_land |= harbour.land(i + di, j + dj) != 0;
      // Beside land the smoothing leans on the water side: within one cell's change of A.
      const double tolerance = beside_land ? 0.8 / (geometry.columns - 1) / 0.2 * 0.5 : 1e-4;
      EXPECT_NEAR(k(i, j), amplitude_m(i) / incident_amplitude_m, tolerance * amplitude_m(i) / incident_amplitude_m)
          << "cell (" << i << ", " << j << ")";
    }
}

TEST(HarbourSiteRelativeWaveHeight, IsEmptyForTooFewFramesOrStillWater) {
  const GridGeometry geometry = testing::wave_geometry(12, 10, 5.0);
  for (const int frames : {5, 20}) {
    const fs::path folder = testing::scratch_folder("_" + std::to_string(frames));
    // 5 frames of waves: too few to say a wave height; 20 frames of still water: no incident sea.
    testing::write_wave_sequence(folder, geometry, frames == 5 ? std::vector<testing::PlaneWave>{{0.5, 0.1, 0.0, 0.8, 0.0}}
                                                                  : std::vector<testing::PlaneWave>{},
                                 frames, 0.5);
    const HarbourSite site = read_harbour_site(sequence::SequenceReader(folder));
    EXPECT_TRUE(site.relative_wave_height.empty()) << frames << " frames";
  }
}

}  // namespace
}  // namespace nearshore::runtime
