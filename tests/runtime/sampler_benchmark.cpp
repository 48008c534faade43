// Not a test: CPU surface queries per second per core (issue 12 target: >= 10 million elevation
// queries per second per core), on a 1024 x 1024 harbour of 2 m cells in a Beaufort 5 sea of
// three 256^2 cascades, one thread. Prints queries/s for points clustered as a ship's hull points
// are (1000 points on a 200 m x 40 m hull moving along a track) and scattered uniformly over the
// harbour and the sea around it, at lattice points and at displaced points, and the full state.
//   build/<dir>/tests/runtime/runtime_sampler_benchmark [seconds per figure, default 1]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "nearshore/core/process_usage.hpp"
#include "nearshore/runtime/deep_water_source.hpp"
#include "nearshore/runtime/surface_sampler.hpp"

using namespace nearshore;
using namespace nearshore::runtime;

namespace {

// Per core: counted against this thread's CPU time (thread_cpu_s, core/process_usage.hpp), not the
// wall clock, so other jobs on a shared machine do not lower the figure (they still cost caches and
// memory bandwidth).
template <class Work>
double rate_per_s(double seconds, std::size_t per_round, Work work) {
  const double start = thread_cpu_s();
  long long rounds = 0;
  do {
    work(rounds);
    ++rounds;
  } while (thread_cpu_s() - start < seconds);
  return static_cast<double>(rounds) * static_cast<double>(per_round) / (thread_cpu_s() - start);
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 1.0;
  constexpr int kSize = 1024;
  constexpr double kSpacing_m = 2.0;
  // The snapshot: two harbour keyframes of linear waves, two deep keyframes.
  auto site = std::make_shared<HarbourSite>();
  GridGeometry geometry;
  geometry.columns = geometry.rows = kSize;
  geometry.spacing_m = kSpacing_m;
  site->harbour = HarbourGrid::open_water(geometry, 12.0f);
  site->width_m = site->height_m = kSize * kSpacing_m;
  site->source_axis = 1;
  site->source_line_m = 100.0;
  site->blend_start_m = 50.0;
  site->blend_width_m = 80.0;
  site->edge_fade_m = 80.0;
  site->frame_interval_s = 0.5;  // keyframes with rates: the harbour is the Hermite in time, as played
  SurfaceSnapshot snapshot;
  snapshot.site = site;
  for (int which = 0; which < 2; ++which) {
    auto keyframe = std::make_shared<HarbourKeyframe>();
    for (Raster<float>* raster : {&keyframe->surface_elevation_m, &keyframe->flux_x_m2_s, &keyframe->flux_y_m2_s,
                                  &keyframe->breaking})
      *raster = Raster<float>(kSize, kSize, 0.0f);
    for (int row = 0; row < kSize; ++row)
      for (int column = 0; column < kSize; ++column) {
        const double phase = 0.08 * column * kSpacing_m + 0.02 * row * kSpacing_m - 0.3 * which;
        keyframe->surface_elevation_m(column, row) = static_cast<float>(0.8 * std::cos(phase));
        keyframe->flux_x_m2_s(column, row) = static_cast<float>(4.0 * std::cos(phase));
      }
    keyframe->surface_elevation_rate_m_s = surface_elevation_rate(site->harbour, keyframe->flux_x_m2_s, keyframe->flux_y_m2_s);
    (which == 0 ? snapshot.harbour_from : snapshot.harbour_to) = keyframe;
  }
  snapshot.harbour_fraction = 0.4;
  const BeaufortSea sea{.force = 5, .grid_size = 256, .cascade_count = 3, .shortest_wavelength_m = 0.5};
  auto field = build_beaufort_field(sea);
  site->choppiness = sea.choppiness;
  // The deep-water synthesis a keyframe costs (4 times mixed: a crossfade's worst case).
  const std::array<ocean::TimedWeight, 4> times = {{{10.0, 0.3}, {10.5, 0.2}, {40.0, 0.1}, {40.5, 0.4}}};
  std::vector<ocean::DeepWaterFrame> frames;
  // The synthesis runs on TBB's threads: its cost is the process's CPU time and the wall time.
  timespec cpu0{}, cpu1{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu0);
  const auto wall0 = std::chrono::steady_clock::now();
  constexpr int kSyntheses = 40;
  for (int i = 0; i < kSyntheses; ++i) field->synthesise_into(times, frames);
  const double synthesis_wall_ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count() / kSyntheses;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu1);
  const double synthesis_cpu_ms =
      1e3 * ((cpu1.tv_sec - cpu0.tv_sec) + 1e-9 * static_cast<double>(cpu1.tv_nsec - cpu0.tv_nsec)) / kSyntheses;
  std::shared_ptr<DeepWaterKeyframe> first_deep;
  for (int which = 0; which < 2; ++which) {
    auto keyframe = std::make_shared<DeepWaterKeyframe>();
    if (which == 0) first_deep = keyframe;
    const ocean::TimedWeight at{12.0 + which / 30.0, 1.0};
    field->synthesise_into(std::span<const ocean::TimedWeight>(&at, 1), keyframe->cascades);
    pack_query_tiles(*keyframe);  // as the streaming engine's worker does
    (which == 0 ? snapshot.deep_from : snapshot.deep_to) = keyframe;
  }
  snapshot.deep_fraction = 0.25;
  // What the engine's worker adds per deep keyframe: the CPU queries' layout (QueryTile).
  const double pack0 = thread_cpu_s();
  constexpr int kPacks = 20;
  for (int i = 0; i < kPacks; ++i) pack_query_tiles(*first_deep);
  const double pack_ms = 1e3 * (thread_cpu_s() - pack0) / kPacks;
  const SurfaceSampler sampler(snapshot);

  // Hull points: 1000 on a 200 m x 40 m hull, placed in turn at 100 positions along a track
  // (the same positions whatever the speed) in one of three waters: inside the harbour (w = 1),
  // in the blending zone (harbour and deep water, the iteration of a displaced query), on the open
  // sea (deep water alone). Scattered: uniform over the harbour and 500 m around it.
  std::vector<SitePoint> hull(1000), scattered(1 << 16);
  std::mt19937 random(1);
  std::uniform_real_distribution<double> along(-100.0, 100.0), across(-20.0, 20.0), anywhere(-500.0, kSize * kSpacing_m + 500.0);
  for (SitePoint& p : scattered) p = {anywhere(random), anywhere(random)};
  std::vector<SitePoint> hull_shape(1000);
  for (SitePoint& p : hull_shape) p = {along(random), across(random)};
  std::vector<double> out(scattered.size());
  std::vector<SurfaceState> states(hull.size());
  double sink = 0.0;
  struct Water {
    const char* name;
    double y0_m;  // the track's northing; x runs from 300 m to 1700 m
  };
  const Water waters[] = {{"inside the harbour", 1000.0}, {"in the blending zone", 190.0}, {"on the open sea", -300.0}};
  const auto place_hull = [&](const Water& water, long long round) {
    const double x0 = 300.0 + 14.0 * static_cast<double>(round % 100);
    for (std::size_t i = 0; i < hull.size(); ++i) hull[i] = {x0 + hull_shape[i].x_m, water.y0_m + hull_shape[i].y_m};
  };
  std::printf("CPU surface queries per CPU-second of one thread (1024 x 1024 harbour, Beaufort 5 sea of 3 x 256^2 "
              "cascades), million/s:\n");
  std::printf("  %-22s %10s %10s %12s\n", "1000 hull points", "lattice", "displaced", "full state");
  for (const Water& water : waters) {
    double rates[3];
    for (int kind = 0; kind < 3; ++kind)
      rates[kind] = rate_per_s(seconds, hull.size(), [&](long long round) {
        place_hull(water, round);
        if (kind == 2) {
          sampler.states(hull, states, ChoppyPoint::kDisplaced);
          sink += states[0].surface_elevation_m;
        } else {
          sampler.elevations_m(hull, out, kind == 0 ? ChoppyPoint::kLattice : ChoppyPoint::kDisplaced);
          sink += out[0];
        }
      });
    std::printf("  %-22s %10.2f %10.2f %12.2f\n", water.name, rates[0] / 1e6, rates[1] / 1e6, rates[2] / 1e6);
  }
  double scattered_rates[2];
  for (int kind = 0; kind < 2; ++kind)
    scattered_rates[kind] = rate_per_s(seconds, scattered.size(), [&](long long) {
      sampler.elevations_m(scattered, out, kind == 0 ? ChoppyPoint::kLattice : ChoppyPoint::kDisplaced);
      sink += out[7];
    });
  std::printf("  %-22s %10.2f %10.2f\n", "65536 scattered points", scattered_rates[0] / 1e6, scattered_rates[1] / 1e6);
  std::printf("deep-water keyframe synthesis (3 x 256^2, 8 channels, 4 times mixed): %.1f ms CPU, %.1f ms wall\n",
              synthesis_cpu_ms, synthesis_wall_ms);
  std::printf("query layout of a deep keyframe (pack_query_tiles, 3 x 256^2): %.2f ms CPU\n", pack_ms);
  std::printf("(checksum %g)\n", sink);
  return 0;
}
