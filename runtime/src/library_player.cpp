#include "nearshore/runtime/library_player.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::runtime {

namespace {

// Serials of blended keyframes: far from the engines' own, so a renderer never mistakes one for
// another (it uploads each serial once).
std::atomic<std::uint64_t> g_blend_serial{std::uint64_t{1} << 62};

// (1 - w) * (harbour of `a` as drawn) + w * (harbour of `b` as drawn), each first interpolated in
// time by its own fraction, for every channel.
std::shared_ptr<const HarbourKeyframe> blend_harbour(const SurfaceSnapshot& a, const SurfaceSnapshot& b, double w) {
  if (!a.harbour_from || !b.harbour_from) return w < 0.5 ? a.harbour_from : b.harbour_from;
  auto blended = std::make_shared<HarbourKeyframe>();
  blended->serial = ++g_blend_serial;
  blended->plan_step = b.harbour_from->plan_step;
  blended->shown = b.harbour_from->shown;
  const auto mix = [&](Raster<float> HarbourKeyframe::*channel, Raster<float>& out) {
    const Raster<float>& a0 = (*a.harbour_from).*channel;
    const Raster<float>& a1 = (*(a.harbour_to ? a.harbour_to : a.harbour_from)).*channel;
    const Raster<float>& b0 = (*b.harbour_from).*channel;
    const Raster<float>& b1 = (*(b.harbour_to ? b.harbour_to : b.harbour_from)).*channel;
    if (a0.size() == 0 || b0.size() != a0.size()) return;
    out = Raster<float>(a0.columns(), a0.rows());
    const float fa = static_cast<float>(a.harbour_fraction), fb = static_cast<float>(b.harbour_fraction);
    const float wa = static_cast<float>(1.0 - w), wb = static_cast<float>(w);
    for (std::size_t i = 0; i < a0.size(); ++i)
      out.values()[i] = wa * ((1.f - fa) * a0.values()[i] + fa * a1.values()[i]) +
                        wb * ((1.f - fb) * b0.values()[i] + fb * b1.values()[i]);
  };
  mix(&HarbourKeyframe::surface_elevation_m, blended->surface_elevation_m);
  mix(&HarbourKeyframe::flux_x_m2_s, blended->flux_x_m2_s);
  mix(&HarbourKeyframe::flux_y_m2_s, blended->flux_y_m2_s);
  mix(&HarbourKeyframe::breaking, blended->breaking);
  mix(&HarbourKeyframe::surface_elevation_rate_m_s, blended->surface_elevation_rate_m_s);
  return blended;
}

// Every cascade of a snapshot's deep water, interpolated in time as drawn and scaled by `weight`.
void add_scaled_cascades(const SurfaceSnapshot& s, double weight, DeepWaterKeyframe& out) {
  if (!s.deep_from) return;
  const DeepWaterKeyframe& from = *s.deep_from;
  const DeepWaterKeyframe& to = s.deep_to ? *s.deep_to : from;
  const float f = static_cast<float>(s.deep_fraction);
  const float w0 = static_cast<float>(weight) * (1.f - f), w1 = static_cast<float>(weight) * f;
  // The split's inside layer (surface_snapshot.hpp): its whole cascades keep their bits, moved
  // past the cascades already in `out`; its straddling ones are scaled like the rest.
  if (from.inside_cascade_mask == to.inside_cascade_mask && out.cascades.size() < 32)
    out.inside_cascade_mask |= from.inside_cascade_mask << out.cascades.size();
  const auto scaled = [&](const ocean::DeepWaterFrame& first, const ocean::DeepWaterFrame& next) {
    ocean::DeepWaterFrame frame = first;
    for (auto channel : {&ocean::DeepWaterFrame::surface_elevation_m, &ocean::DeepWaterFrame::displacement_x_m,
                         &ocean::DeepWaterFrame::displacement_y_m, &ocean::DeepWaterFrame::slope_x,
                         &ocean::DeepWaterFrame::slope_y, &ocean::DeepWaterFrame::displacement_xx,
                         &ocean::DeepWaterFrame::displacement_yy, &ocean::DeepWaterFrame::displacement_xy,
                         &ocean::DeepWaterFrame::flux_x_m2_s, &ocean::DeepWaterFrame::flux_y_m2_s}) {
      std::vector<float>& values = frame.*channel;
      const std::vector<float>& later = next.*channel;
      if (later.size() != values.size()) {
        values.clear();
        continue;
      }
      for (std::size_t i = 0; i < values.size(); ++i) values[i] = w0 * values[i] + w1 * later[i];
    }
    return frame;
  };
  for (std::size_t c = 0; c < from.cascades.size() && c < to.cascades.size(); ++c)
    out.cascades.push_back(scaled(from.cascades[c], to.cascades[c]));
  for (std::size_t c = 0; c < from.inside_cascades.size() && c < to.inside_cascades.size(); ++c)
    out.inside_cascades.push_back(scaled(from.inside_cascades[c], to.inside_cascades[c]));
}

double smoothstep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

}  // namespace

struct LibraryPlayer::Impl {
  std::filesystem::path folder;
  sequence::LibraryIndex index;
  StreamingOptions options;
  std::unique_ptr<StreamingEngine> shown, fading_out;  // fading_out: the old state during a crossfade
  std::string shown_id;
  double crossfade_s = 0.0, fade_start_s = -1.0;  // fade_start_s < 0: starts at the next advance
  double weight = 1.0;
  mutable std::mutex snapshot_mutex;
  SurfaceSnapshot current;

  int nearest(const sequence::SeaConditions& conditions) const {
    const sequence::LibrarySelection selection = sequence::select_library_states(index, conditions);
    if (selection.nearest < 0)
      throw Error((folder / "library.json").string(), "has no baked sea state to play",
                  "finish the library's bakes (run the library again: it bakes only what is missing)");
    return selection.nearest;
  }
  std::unique_ptr<StreamingEngine> open(int state) const {
    const sequence::LibraryIndex::State& chosen = index.states[static_cast<std::size_t>(state)];
    auto engine = std::make_unique<StreamingEngine>(folder / chosen.sequence, options);
    return engine;
  }
};

LibraryPlayer::LibraryPlayer(const std::filesystem::path& library_folder, const sequence::SeaConditions& conditions,
                             StreamingOptions options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.folder = library_folder;
  m.index = sequence::read_library_index(library_folder);
  m.options = std::move(options);
  const int state = m.nearest(conditions);
  m.shown = m.open(state);
  m.shown_id = m.index.states[static_cast<std::size_t>(state)].id;
}

LibraryPlayer::~LibraryPlayer() = default;

const std::string& LibraryPlayer::request(const sequence::SeaConditions& conditions, double crossfade_s) {
  Impl& m = *impl_;
  if (!(crossfade_s >= 0.0) || crossfade_s > 3600.0)
    throw Error(fmt::format("LibraryPlayer::request crossfade_s = {}", crossfade_s), "is outside 0-3600 s",
                "give the crossfade's length in seconds of display time (0: a cut)");
  const int state = m.nearest(conditions);
  const std::string& id = m.index.states[static_cast<std::size_t>(state)].id;
  if (id == m.shown_id) return m.shown_id;
  std::unique_ptr<StreamingEngine> next = m.open(state);
  m.fading_out = crossfade_s > 0.0 ? std::move(m.shown) : nullptr;  // a fade under way ends at once
  m.shown = std::move(next);
  m.shown_id = id;
  m.crossfade_s = crossfade_s;
  m.fade_start_s = -1.0;
  m.weight = crossfade_s > 0.0 ? 0.0 : 1.0;
  return m.shown_id;
}

bool LibraryPlayer::advance_to(double display_time_s) {
  Impl& m = *impl_;
  bool planned = m.shown->advance_to(display_time_s);
  SurfaceSnapshot next = m.shown->snapshot();
  if (m.fading_out) {
    if (m.fade_start_s < 0.0) m.fade_start_s = display_time_s;
    m.weight = smoothstep((display_time_s - m.fade_start_s) / m.crossfade_s);
    if (m.weight >= 1.0) {
      m.fading_out.reset();
    } else {
      planned = m.fading_out->advance_to(display_time_s) && planned;
      const SurfaceSnapshot old = m.fading_out->snapshot();
      next.harbour_from = next.harbour_to = blend_harbour(old, next, m.weight);
      next.harbour_fraction = 0.0;
      if (old.deep_from || next.deep_from) {
        auto deep = std::make_shared<DeepWaterKeyframe>();
        deep->serial = ++g_blend_serial;
        deep->display_time_s = display_time_s;
        add_scaled_cascades(old, 1.0 - m.weight, *deep);
        add_scaled_cascades(next, m.weight, *deep);
        deep->still_water_depth_m = next.deep_from ? next.deep_from->still_water_depth_m : old.deep_from->still_water_depth_m;
        pack_query_tiles(*deep);
        next.deep_from = next.deep_to = deep;
        next.deep_fraction = 0.0;
      }
    }
  } else {
    m.weight = 1.0;
  }
  {
    const std::lock_guard<std::mutex> lock(m.snapshot_mutex);
    std::swap(m.current, next);
  }
  return planned;
}

bool LibraryPlayer::wait_until_ready(double display_time_s, std::chrono::milliseconds timeout) {
  Impl& m = *impl_;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  if (!m.shown->wait_until_ready(display_time_s, timeout)) return false;
  if (!m.fading_out) return true;
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
  return m.fading_out->wait_until_ready(display_time_s, std::max(left, std::chrono::milliseconds(0)));
}

SurfaceSnapshot LibraryPlayer::snapshot() const {
  const std::lock_guard<std::mutex> lock(impl_->snapshot_mutex);
  return impl_->current;
}

StreamingEngine& LibraryPlayer::engine() { return *impl_->shown; }
const StreamingEngine& LibraryPlayer::engine() const { return *impl_->shown; }
const std::string& LibraryPlayer::state_id() const { return impl_->shown_id; }
double LibraryPlayer::crossfade_weight() const { return impl_->weight; }
const sequence::LibraryIndex& LibraryPlayer::index() const { return impl_->index; }

PlayedSea::PlayedSea(const std::filesystem::path& folder, const sequence::SeaConditions& conditions,
                     StreamingOptions options) {
  if (std::filesystem::is_regular_file(folder / "library.json"))
    library_ = std::make_unique<LibraryPlayer>(folder, conditions, std::move(options));
  else
    single_ = std::make_unique<StreamingEngine>(folder, std::move(options));
}

}  // namespace nearshore::runtime
