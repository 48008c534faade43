#include "nearshore/runtime/streaming_engine.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <numbers>
#include <optional>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "keyframe_pool.hpp"
#include "nearshore/core/error.hpp"
#include "nearshore/core/process_usage.hpp"
#include "nearshore/runtime/harbour_site.hpp"

namespace nearshore::runtime {

namespace {

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double mebibytes(std::size_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); }

struct HarbourEntry {
  long long index = 0;  // plan step
  PlanStep step;
  std::shared_ptr<const HarbourKeyframe> keyframe;
};

struct DeepEntry {
  long long index = 0;  // display time = index * interval
  std::shared_ptr<const DeepWaterKeyframe> keyframe;
};

// Up to `count` keyframes of `ring` after `shown` (all from the front when nothing is shown).
template <class Entry, class Keyframe>
std::vector<std::shared_ptr<const Keyframe>> keyframes_after(const std::deque<Entry>& ring,
                                                             const std::shared_ptr<const Keyframe>& shown, int count) {
  std::vector<std::shared_ptr<const Keyframe>> upcoming;
  bool past_shown = !shown;
  for (const Entry& entry : ring) {
    if (static_cast<int>(upcoming.size()) >= count) break;
    if (past_shown) upcoming.push_back(entry.keyframe);
    if (shown && entry.keyframe->serial == shown->serial) past_shown = true;
  }
  return upcoming;
}

// The entry of `index` in a ring of consecutive indices, or nullptr.
template <class Entry>
const Entry* find(const std::deque<Entry>& ring, long long index) {
  if (ring.empty() || index < ring.front().index) return nullptr;
  const long long offset = index - ring.front().index;
  if (offset >= static_cast<long long>(ring.size())) return nullptr;
  return &ring[static_cast<std::size_t>(offset)];
}

// A ring of keyframes of consecutive indices that a worker fills ahead of the display time (the
// harbour's steps, the deep water's keyframes): one definition for both. Every member is guarded
// by StreamingEngine::Impl::mutex.
template <class Entry>
struct KeyframeRing {
  std::deque<Entry> entries;
  long long next = 0;        // the index the worker makes next
  long long generation = 0;  // bumped by a restart: a keyframe made for an older one is dropped
  int capacity = 0;

  const Entry* find(long long index) const { return runtime::find(entries, index); }
  bool holds_pair(long long index) const { return find(index) && find(index + 1); }
  bool has_room() const { return static_cast<int>(entries.size()) < capacity; }
  bool full() const { return static_cast<int>(entries.size()) >= capacity; }
  int fill() const { return static_cast<int>(entries.size()); }
  // Drops the entries before `index` (shown and gone); true when one was dropped.
  bool consume_before(long long index) {
    bool dropped = false;
    while (!entries.empty() && entries.front().index < index) {
      entries.pop_front();
      dropped = true;
    }
    return dropped;
  }
  // Restarts the ring at `index` when it cannot reach it: a time behind it (a seek back), or a
  // worker further behind than a ring's length (it would make keyframes no one will show). True
  // when it restarted.
  bool restart_if_unreachable(long long index) {
    const bool unreachable = entries.empty() ? next > index || next < index - capacity : entries.front().index > index;
    if (!unreachable) return false;
    entries.clear();
    next = index;
    ++generation;
    return true;
  }
  // What the worker made for `made_generation`: kept, and the worker moves on, unless a restart
  // came in between.
  void accept(long long made_generation, Entry entry) {
    if (made_generation != generation) return;
    entries.push_back(std::move(entry));
    ++next;
  }
};

void swap_fields(HarbourKeyframe& keyframe, sequence::Frame& frame) {
  std::swap(keyframe.surface_elevation_m, frame.surface_elevation_m);
  std::swap(keyframe.flux_x_m2_s, frame.flux_x_m2_s);
  std::swap(keyframe.flux_y_m2_s, frame.flux_y_m2_s);
  std::swap(keyframe.breaking, frame.breaking);
}

// The keyframe's d eta / dt (surface_snapshot.hpp) from its own fluxes. Inside a crossfade the
// shown field is (1 - alpha) source + alpha target with alpha rising by 1 / (c + 1) a step
// (loop_playback.hpp), so its rate also holds d alpha / dt (target - source).
void fill_rate(HarbourKeyframe& keyframe, const HarbourSite& site, const PlanStep& step, const sequence::Frame* source,
               const sequence::Frame* target) {
  const GridGeometry& g = site.harbour.geometry;
  if (keyframe.flux_x_m2_s.columns() != g.columns || keyframe.flux_x_m2_s.rows() != g.rows ||
      keyframe.flux_y_m2_s.columns() != g.columns || keyframe.flux_y_m2_s.rows() != g.rows) {
    keyframe.surface_elevation_rate_m_s = Raster<float>();  // no fluxes stored: linear in time
    return;
  }
  keyframe.surface_elevation_rate_m_s = surface_elevation_rate(site.harbour, keyframe.flux_x_m2_s, keyframe.flux_y_m2_s);
  if (!step.in_crossfade || !source || !target || !(site.frame_interval_s > 0.0) || step.jump_crossfade_frames < 1) return;
  const Raster<float>& a = source->surface_elevation_m;
  const Raster<float>& b = target->surface_elevation_m;
  if (a.size() != keyframe.surface_elevation_rate_m_s.size() || b.size() != a.size()) return;
  const double alpha_rate = 1.0 / ((step.jump_crossfade_frames + 1) * site.frame_interval_s);
  float* rate = keyframe.surface_elevation_rate_m_s.data();
  for (std::size_t i = 0; i < a.size(); ++i) rate[i] += static_cast<float>(alpha_rate * (b.values()[i] - a.values()[i]));
}

}  // namespace

struct StreamingEngine::Impl {
  enum class DeepKind { kNone, kBake, kBeaufort };

  Impl(const std::filesystem::path& folder_in, StreamingOptions options_in)
      : folder(folder_in), options(std::move(options_in)), reader(folder) {}

  std::filesystem::path folder;
  StreamingOptions options;
  sequence::SequenceReader reader;  // const methods only: safe from every thread
  std::shared_ptr<const HarbourSite> site;
  double frame_interval_s = 0.0, deep_interval_s = 0.0;
  PlaybackPlan plan_template = PlaybackPlan::frame_order(1);
  std::string plan_message;

  DeepKind deep_kind = DeepKind::kNone;
  bool deep_with_flux = false;
  double deep_depth_m = 0.0;
  std::size_t bytes_harbour = 0, bytes_deep = 0;
  KeyframePool<HarbourKeyframe> harbour_pool;
  KeyframePool<DeepWaterKeyframe> deep_pool;
  std::atomic<std::uint64_t> serial{0};

  // Shared between the render thread, the worker and the builder: guarded by `mutex`, which is
  // never held across decoding, synthesis or I/O.
  mutable std::mutex mutex;
  std::condition_variable work_cv, ready_cv;
  KeyframeRing<HarbourEntry> harbour_ring;
  KeyframeRing<DeepEntry> deep_ring;
  bool stop = false;
  StreamingStats counters;
  std::shared_ptr<const ocean::RecordedDeepWater> record;  // the current field's lattices (slow path)
  std::unique_ptr<ocean::DeepWaterField> pending_field;    // from the builder, swapped in by the worker
  bool has_pending_field = false;
  std::shared_ptr<const ocean::RecordedDeepWater> pending_record;

  // The render thread's snapshot (written by advance_to, read by snapshot() on any thread).
  mutable std::mutex snapshot_mutex;
  SurfaceSnapshot current;

  // Worker-only state.
  PlaybackPlan harbour_plan = PlaybackPlan::frame_order(1), deep_plan = PlaybackPlan::frame_order(1);
  std::unique_ptr<ocean::DeepWaterField> field;
  // The split's inside layer (deep_water_source.hpp): its straddling cascades as a field of their
  // own (worker's and slow path's: a field's synthesis is not reentrant). Static for the sequence.
  std::optional<SpectrumSplitRecord> split;
  std::shared_ptr<const DeepWaterInsideLayer> inside_layer;
  std::unique_ptr<ocean::DeepWaterField> inside_field, slow_inside_field;
  sequence::Frame source_frame, target_frame, blended_frame;
  std::shared_ptr<const HarbourKeyframe> last_good;
  std::thread harbour_worker, deep_worker;

  // The Beaufort builder thread.
  std::thread builder;
  std::mutex builder_mutex;
  std::condition_variable builder_cv;
  std::optional<BeaufortSea> builder_request;
  bool builder_stop = false;

  // The slow path (snapshot_at, lockstep, the first advance): keyframes made on the calling
  // thread, serialised. In lockstep the last few are kept, so that consecutive display frames
  // (k, k + 1 then k + 1, k + 2) decode each step once.
  std::mutex slow_mutex;
  PlaybackPlan slow_plan = PlaybackPlan::frame_order(1);
  std::unique_ptr<ocean::DeepWaterField> slow_field;
  std::shared_ptr<const ocean::RecordedDeepWater> slow_field_record;
  std::deque<HarbourEntry> slow_harbour;
  std::deque<DeepEntry> slow_deep;
  static constexpr std::size_t kSlowKept = 3;

  // One worker per ring: harbour decoding (I/O and EXR) and deep-water synthesis (FFT) run on two
  // cores at once; each sleeps while its ring is full.
  void run_worker(bool harbour);
  void run_builder();
  // Harbour keyframe of a plan step: the frame, or the planned crossfade blend; a frame that
  // cannot be read is replaced by the last good keyframe (held). `message` gets the problem.
  void decode_harbour(const PlanStep& step, HarbourKeyframe& keyframe, std::string& message);
  // Deep keyframe `index` (display time index * interval) from `deep_field` (null: flat), and the
  // split's inside layer from `inside` (null: none; only with the bake's field).
  void synthesise_deep(long long index, PlaybackPlan& plan, ocean::DeepWaterField* deep_field,
                       ocean::DeepWaterField* inside, DeepWaterKeyframe& keyframe);
  // Drops keyframes before (k, j) when `consume`, and restarts the worker at k (j) when the rings
  // cannot reach it: a time behind them, or far ahead of the worker. Caller holds `mutex`.
  void schedule_locked(long long k, long long j, bool consume);
  bool ready_locked(long long k, long long j) const;
  // The slow path: fills what `result` lacks of harbour steps k, k + 1 (need_harbour) and deep
  // keyframes j, j + 1 (need_deep) on the calling thread. Returns what it made and held.
  struct SlowResult {
    int made = 0, held = 0;
    std::string message;
  };
  SlowResult make_synchronously(long long k, long long j, bool need_harbour, bool need_deep, SurfaceSnapshot& result);
  std::shared_ptr<const HarbourKeyframe> slow_harbour_keyframe(long long s, SlowResult& out);
  void count_slow(const SlowResult& made);  // takes `mutex`
  void set_message_locked(std::string message) { counters.last_message = std::move(message); }
};

void StreamingEngine::Impl::decode_harbour(const PlanStep& step, HarbourKeyframe& keyframe, std::string& message) {
  keyframe.serial = ++serial;
  keyframe.plan_step = step.step;
  keyframe.shown = step.shown;
  keyframe.held = false;
  if (options.before_decode) options.before_decode(step.step);
  const sequence::ChannelSelection all = sequence::ChannelSelection::all();
  int reading = step.shown.source_frame;
  try {
    reader.read_frame_into(reading, source_frame, all, options.verify);
    if (step.in_crossfade) {
      // The planned crossfade: the same weight for every channel (loop_playback.hpp).
      reading = step.shown.target_frame;
      reader.read_frame_into(reading, target_frame, all, options.verify);
      sequence::blend_frames(source_frame, target_frame, step.shown.target_weight, blended_frame);
      swap_fields(keyframe, blended_frame);
      fill_rate(keyframe, *site, step, &source_frame, &target_frame);
    } else {
      swap_fields(keyframe, source_frame);
      fill_rate(keyframe, *site, step, nullptr, nullptr);
    }
  } catch (const std::exception& error) {
    // Hold the previous good keyframe in its place (its memory is reused: the same sizes).
    keyframe.held = true;
    const GridGeometry& g = reader.geometry();
    if (last_good) {
      keyframe.surface_elevation_m = last_good->surface_elevation_m;
      keyframe.flux_x_m2_s = last_good->flux_x_m2_s;
      keyframe.flux_y_m2_s = last_good->flux_y_m2_s;
      keyframe.breaking = last_good->breaking;
      keyframe.surface_elevation_rate_m_s = last_good->surface_elevation_rate_m_s;
    } else {
      for (Raster<float>* raster : {&keyframe.surface_elevation_m, &keyframe.flux_x_m2_s, &keyframe.flux_y_m2_s,
                                    &keyframe.breaking, &keyframe.surface_elevation_rate_m_s})
        *raster = Raster<float>(g.columns, g.rows, 0.0f);
    }
    message = fmt::format("{}; plan step {} holds {} in its place", error.what(), step.step,
                          last_good ? fmt::format("the keyframe of step {}", last_good->plan_step)
                                    : std::string("a flat sea"));
  }
}

void StreamingEngine::Impl::synthesise_deep(long long index, PlaybackPlan& plan, ocean::DeepWaterField* deep_field,
                                            ocean::DeepWaterField* inside, DeepWaterKeyframe& keyframe) {
  keyframe.serial = ++serial;
  keyframe.display_time_s = static_cast<double>(index) * deep_interval_s;
  keyframe.still_water_depth_m = deep_depth_m;
  keyframe.inside_cascade_mask = 0;
  keyframe.inside_cascades.clear();
  keyframe.query_tiles.clear();
  if (!deep_field) {
    keyframe.cascades.clear();  // a calm sea
    return;
  }
  if (deep_kind == DeepKind::kBake) {
    // The bake's own field at the bake times the harbour frames show (deep_water_source.hpp).
    const double steps = keyframe.display_time_s / frame_interval_s;
    const long long k = static_cast<long long>(std::floor(steps));
    const PlanStep now = plan.step(k);
    const PlanStep next = plan.step(k + 1);
    const BakeTimes times =
        bake_times(now, next, steps - static_cast<double>(k), frame_interval_s, reader.manifest().first_frame_time_s);
    deep_field->synthesise_into(times.span(), keyframe.cascades, deep_with_flux);
    if (inside_layer) {
      // The split: the same bake times, so the layer is the same waves the field shows outside.
      keyframe.inside_cascade_mask = inside_layer->whole_cascade_mask;
      if (inside) inside->synthesise_into(times.span(), keyframe.inside_cascades, deep_with_flux);
    }
  } else {
    // A Beaufort sea of its own: its time is the display time.
    const ocean::TimedWeight at{keyframe.display_time_s, 1.0};
    deep_field->synthesise_into(std::span<const ocean::TimedWeight>(&at, 1), keyframe.cascades, deep_with_flux);
  }
  // The CPU queries' layout of the cascades (surface_snapshot.hpp QueryTile), here on the worker
  // (about 1 ms for 3 x 256^2) rather than in every host's sampler.
  pack_query_tiles(keyframe);
}

std::shared_ptr<const HarbourKeyframe> StreamingEngine::Impl::slow_harbour_keyframe(long long s, SlowResult& out) {
  for (const HarbourEntry& kept : slow_harbour)
    if (kept.index == s) return kept.keyframe;
  auto keyframe = std::make_shared<HarbourKeyframe>();
  keyframe->serial = ++serial;
  keyframe->plan_step = s;
  const PlanStep step = slow_plan.step(s);
  keyframe->shown = step.shown;
  // A frame that cannot be read is replaced as the worker replaces it, but by a rule of the step
  // alone (the nearest earlier step that reads, within 8; else a flat sea), so that what lockstep
  // shows never depends on what was shown before.
  const sequence::ChannelSelection all = sequence::ChannelSelection::all();
  std::string problem;
  for (long long back = 0; back <= 8 && s - back >= 0; ++back) {
    const PlanStep tried = back == 0 ? step : slow_plan.step(s - back);
    try {
      sequence::Frame source = reader.read_frame(tried.shown.source_frame, all, options.verify);
      sequence::Frame shown;
      if (tried.in_crossfade) {
        const sequence::Frame target = reader.read_frame(tried.shown.target_frame, all, options.verify);
        sequence::blend_frames(source, target, tried.shown.target_weight, shown);
        swap_fields(*keyframe, shown);
        fill_rate(*keyframe, *site, tried, &source, &target);
      } else {
        swap_fields(*keyframe, source);
        fill_rate(*keyframe, *site, tried, nullptr, nullptr);
      }
      if (back > 0) {
        keyframe->held = true;
        ++out.held;
        out.message = fmt::format("{}; plan step {} holds the keyframe of step {} in its place", problem, s, s - back);
      }
      ++out.made;
      if (options.lockstep) {
        slow_harbour.push_back({s, step, keyframe});
        if (slow_harbour.size() > kSlowKept) slow_harbour.pop_front();
      }
      return keyframe;
    } catch (const std::exception& error) {
      if (back == 0) problem = error.what();
    }
  }
  const GridGeometry& g = reader.geometry();
  for (Raster<float>* raster : {&keyframe->surface_elevation_m, &keyframe->flux_x_m2_s, &keyframe->flux_y_m2_s,
                                &keyframe->breaking, &keyframe->surface_elevation_rate_m_s})
    *raster = Raster<float>(g.columns, g.rows, 0.0f);
  keyframe->held = true;
  ++out.held;
  ++out.made;
  out.message = fmt::format("{}; plan step {} holds a flat sea in its place", problem, s);
  return keyframe;
}

StreamingEngine::Impl::SlowResult StreamingEngine::Impl::make_synchronously(long long k, long long j, bool need_harbour,
                                                                             bool need_deep, SurfaceSnapshot& result) {
  SlowResult out;
  std::shared_ptr<const ocean::RecordedDeepWater> field_record;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    field_record = record;
  }
  const std::lock_guard<std::mutex> slow(slow_mutex);
  if (need_harbour) {
    result.harbour_from = slow_harbour_keyframe(k, out);
    result.harbour_to = slow_harbour_keyframe(k + 1, out);
  }
  if (need_deep) {
    if (field_record != slow_field_record) {
      slow_field = field_record ? std::make_unique<ocean::DeepWaterField>(*field_record) : nullptr;
      slow_field_record = field_record;
      slow_deep.clear();
    }
    for (long long index : {j, j + 1}) {
      std::shared_ptr<const DeepWaterKeyframe> made;
      for (const DeepEntry& kept : slow_deep)
        if (kept.index == index) made = kept.keyframe;
      if (!made) {
        auto keyframe = std::make_shared<DeepWaterKeyframe>();
        synthesise_deep(index, slow_plan, slow_field.get(), slow_inside_field.get(), *keyframe);
        made = keyframe;
        ++out.made;
        if (options.lockstep) {
          slow_deep.push_back({index, made});
          if (slow_deep.size() > kSlowKept) slow_deep.pop_front();
        }
      }
      (index == j ? result.deep_from : result.deep_to) = std::move(made);
    }
  }
  return out;
}

void StreamingEngine::Impl::count_slow(const SlowResult& made) {
  const std::lock_guard<std::mutex> lock(mutex);
  counters.synchronous_keyframes += made.made;
  counters.bad_frames_held += made.held;
  if (!made.message.empty()) set_message_locked(made.message);
}

bool StreamingEngine::Impl::ready_locked(long long k, long long j) const {
  return harbour_ring.holds_pair(k) && (deep_kind == DeepKind::kNone || deep_ring.holds_pair(j));
}

void StreamingEngine::Impl::schedule_locked(long long k, long long j, bool consume) {
  bool wake = false;
  if (consume) {
    wake |= harbour_ring.consume_before(k);
    wake |= deep_ring.consume_before(j);
  }
  wake |= harbour_ring.restart_if_unreachable(k);
  if (deep_kind != DeepKind::kNone) wake |= deep_ring.restart_if_unreachable(j);
  if (wake) work_cv.notify_all();
}

void StreamingEngine::Impl::run_worker(bool harbour) {
  std::unique_lock<std::mutex> lock(mutex);
  while (!stop) {
    if (!harbour && has_pending_field) {
      field = std::move(pending_field);
      record = pending_record;
      has_pending_field = false;
    }
    const bool room = harbour ? harbour_ring.has_room() : deep_ring.has_room();
    if (!room) {
      work_cv.wait(lock);
      continue;
    }
    if (harbour) {
      const long long index = harbour_ring.next, generation = harbour_ring.generation;
      lock.unlock();
      const double wall0 = wall_seconds(), cpu0 = thread_cpu_s();
      const PlanStep step = harbour_plan.step(index);
      std::unique_ptr<HarbourKeyframe> keyframe = harbour_pool.acquire();
      std::string message;
      decode_harbour(step, *keyframe, message);
      const bool held = keyframe->held;
      std::shared_ptr<const HarbourKeyframe> published = harbour_pool.publish(std::move(keyframe));
      if (!held) last_good = published;
      const double wall1 = wall_seconds(), cpu1 = thread_cpu_s();
      lock.lock();
      counters.decode_seconds += wall1 - wall0;
      counters.decode_cpu_seconds += cpu1 - cpu0;
      ++counters.keyframes_decoded;
      if (held) {
        ++counters.bad_frames_held;
        set_message_locked(std::move(message));
      }
      harbour_ring.accept(generation, {index, step, std::move(published)});
    } else {
      const long long index = deep_ring.next, generation = deep_ring.generation;
      ocean::DeepWaterField* deep_field = field.get();
      lock.unlock();
      const double wall0 = wall_seconds(), cpu0 = thread_cpu_s();
      std::unique_ptr<DeepWaterKeyframe> keyframe = deep_pool.acquire();
      std::string message;
      try {
        synthesise_deep(index, deep_plan, deep_field, inside_field.get(), *keyframe);
      } catch (const std::exception& error) {
        keyframe->cascades.clear();
        keyframe->inside_cascade_mask = 0;
        keyframe->inside_cascades.clear();
        keyframe->query_tiles.clear();
        message = fmt::format("deep water at {} s: {}; a calm sea is shown", keyframe->display_time_s, error.what());
      }
      std::shared_ptr<const DeepWaterKeyframe> published = deep_pool.publish(std::move(keyframe));
      const double wall1 = wall_seconds(), cpu1 = thread_cpu_s();
      lock.lock();
      counters.deep_seconds += wall1 - wall0;
      counters.deep_cpu_seconds += cpu1 - cpu0;
      ++counters.deep_keyframes_synthesised;
      if (!message.empty()) set_message_locked(std::move(message));
      deep_ring.accept(generation, {index, std::move(published)});
    }
    // Let go of keyframes outside the lock: the last one returns to its pool.
    lock.unlock();
    ready_cv.notify_all();
    lock.lock();
  }
}

void StreamingEngine::Impl::run_builder() {
  std::unique_lock<std::mutex> lock(builder_mutex);
  while (true) {
    builder_cv.wait(lock, [&] { return builder_stop || builder_request.has_value(); });
    if (builder_stop) return;
    const BeaufortSea sea = *builder_request;
    builder_request.reset();
    lock.unlock();
    std::unique_ptr<ocean::DeepWaterField> built;
    std::string message;
    try {
      built = build_beaufort_field(sea);
    } catch (const std::exception& error) {
      message = fmt::format("{}; the previous sea stays", error.what());
    }
    {
      const std::lock_guard<std::mutex> guard(mutex);
      if (message.empty()) {
        pending_record = built ? std::make_shared<const ocean::RecordedDeepWater>(built->record()) : nullptr;
        // As in the constructor: the same construction as the slow path's field.
        pending_field = pending_record ? std::make_unique<ocean::DeepWaterField>(*pending_record) : nullptr;
        has_pending_field = true;
      } else {
        set_message_locked(std::move(message));
      }
    }
    work_cv.notify_all();
    lock.lock();
  }
}

StreamingEngine::StreamingEngine(const std::filesystem::path& folder, StreamingOptions options)
    : impl_(std::make_unique<Impl>(folder, std::move(options))) {
  Impl& m = *impl_;
  const StreamingOptions& o = m.options;
  const std::string subject = fmt::format("streaming engine for {}", folder.string());
  if (!(o.deep_water_interval_s > 0.0) || !std::isfinite(o.deep_water_interval_s))
    throw Error(subject, fmt::format("StreamingOptions::deep_water_interval_s = {} s", o.deep_water_interval_s),
                "give a positive interval, e.g. 1/30 s");
  if (o.ring_capacity != 0 && o.ring_capacity < 2)
    throw Error(subject, fmt::format("StreamingOptions::ring_capacity = {}", o.ring_capacity),
                "hold at least 2 keyframes (the one shown and the next), or 0 for automatic");
  if (o.deep_water_ring_capacity != 0 && o.deep_water_ring_capacity < 2)
    throw Error(subject, fmt::format("StreamingOptions::deep_water_ring_capacity = {}", o.deep_water_ring_capacity),
                "hold at least 2 keyframes, or 0 for automatic");
  m.frame_interval_s = m.reader.frame_interval_s();
  m.deep_interval_s = o.deep_water_interval_s;
  if (m.reader.frame_count() < 1) throw Error(folder.string(), "has no frames", "bake it again with a longer duration");

  // 1. The site and the plan (a plan that cannot be made falls back to frame order, said).
  auto site = std::make_shared<HarbourSite>(read_harbour_site(m.reader, o.edge_fade_m, o.verify));
  try {
    m.plan_template = PlaybackPlan(folder, o.plan, o.seed);
  } catch (const Error& error) {
    m.plan_template = PlaybackPlan::frame_order(m.reader.frame_count());
    m.plan_message = fmt::format("{}; playing the frames in order instead", error.what());
  }
  m.harbour_plan = m.deep_plan = m.slow_plan = m.plan_template;
  m.counters.plan = m.plan_template.description();
  m.counters.last_message = m.plan_message;

  // 2. The deep water: the bake's own field, else (or on request) the Beaufort sea.
  std::optional<ocean::RecordedDeepWater> recorded;
  if (o.deep_water == DeepWaterChoice::kBakeElseBeaufort) recorded = read_recorded_deep_water(m.reader, o.verify);
  if (recorded) {
    m.deep_kind = Impl::DeepKind::kBake;
    m.field = std::make_unique<ocean::DeepWaterField>(*recorded);
    m.record = std::make_shared<const ocean::RecordedDeepWater>(std::move(*recorded));
    m.deep_depth_m = m.record->still_water_depth_m;
    // 2b. The split (issue 14 item 1): the components the bake left to the deep-water layer are
    // drawn inside the rectangle too, on top of the frames, band-limited to above the bake's band.
    m.split = read_spectrum_split(m.reader.manifest(), (folder / "manifest.json").string());
    if (m.split) {
      auto layer = std::make_shared<DeepWaterInsideLayer>(
          split_deep_water(*m.record, 2.0 * std::numbers::pi * m.split->split_frequency_hz));
      if (!layer->straddling.cascades.empty()) {
        m.inside_field = std::make_unique<ocean::DeepWaterField>(layer->straddling);
        m.slow_inside_field = std::make_unique<ocean::DeepWaterField>(layer->straddling);
      }
      if (layer->component_count > 0) {
        m.inside_layer = std::move(layer);
      } else {
        m.inside_field.reset();
        m.slow_inside_field.reset();
      }
    }
  } else if (o.deep_water != DeepWaterChoice::kNone) {
    m.deep_kind = Impl::DeepKind::kBeaufort;
    m.field = build_beaufort_field(o.beaufort);
    if (m.field) {
      // The worker's field is rebuilt from the record as the slow path's is, so that both make
      // the same keyframe bit for bit (lockstep mixes them).
      m.record = std::make_shared<const ocean::RecordedDeepWater>(m.field->record());
      m.field = std::make_unique<ocean::DeepWaterField>(*m.record);
    }
    site->choppiness = o.beaufort.choppiness;
    m.deep_depth_m = 0.0;
  }
  // Fluxes (two more FFTs) only where they give a velocity: a field of finite depth.
  m.deep_with_flux = m.deep_depth_m > 0.0;
  m.site = site;
  site_ = site;

  // 3. The rings, sized by time and bounded in bytes.
  const GridGeometry& g = m.reader.geometry();
  m.bytes_harbour = std::size_t{4} * sizeof(float) * static_cast<std::size_t>(g.columns) * static_cast<std::size_t>(g.rows);
  if (m.record)
    for (const ocean::RecordedCascade& cascade : m.record->cascades)
      // The channels, plus the CPU queries' layout of each cascade (4 int16 a node: QueryTile).
      m.bytes_deep += ((m.deep_with_flux ? 10u : 8u) * sizeof(float) + 4u * sizeof(std::int16_t)) *
                      static_cast<std::size_t>(cascade.grid_size) * static_cast<std::size_t>(cascade.grid_size);
  if (m.inside_layer)
    for (const ocean::RecordedCascade& cascade : m.inside_layer->straddling.cascades)
      m.bytes_deep += (m.deep_with_flux ? 10u : 8u) * sizeof(float) * static_cast<std::size_t>(cascade.grid_size) *
                      static_cast<std::size_t>(cascade.grid_size);
  if (o.ring_capacity > 0) {
    m.harbour_ring.capacity = o.ring_capacity;
  } else {
    m.harbour_ring.capacity = std::clamp(static_cast<int>(std::ceil(o.ring_lookahead_s / m.frame_interval_s)) + 2, 4, 64);
    while (m.harbour_ring.capacity > 3 && static_cast<std::size_t>(m.harbour_ring.capacity) * m.bytes_harbour > o.max_ring_bytes)
      --m.harbour_ring.capacity;
  }
  if (o.deep_water_ring_capacity > 0) {
    m.deep_ring.capacity = o.deep_water_ring_capacity;
  } else {
    const double span_s = m.harbour_ring.capacity * m.frame_interval_s;
    m.deep_ring.capacity = std::clamp(static_cast<int>(std::ceil(span_s / m.deep_interval_s)) + 2, 4, 256);
    while (m.deep_ring.capacity > 3 &&
           static_cast<std::size_t>(m.deep_ring.capacity) * m.bytes_deep > std::min(o.max_ring_bytes, o.max_deep_ring_bytes))
      --m.deep_ring.capacity;
  }
  m.counters.ring_capacity = m.harbour_ring.capacity;
  m.counters.deep_ring_capacity = m.deep_kind == Impl::DeepKind::kNone ? 0 : m.deep_ring.capacity;
  m.counters.harbour_keyframe_bytes = m.bytes_harbour;
  m.counters.deep_keyframe_bytes = m.bytes_deep;
  m.counters.frame_interval_s = m.frame_interval_s;
  m.current.site = site;

  // 4. The threads: the worker decodes OpenEXR on its own thread only (no OpenEXR pool).
  sequence::set_exr_worker_threads(0);
  m.harbour_worker = std::thread([&m] { m.run_worker(true); });
  if (m.deep_kind != Impl::DeepKind::kNone) m.deep_worker = std::thread([&m] { m.run_worker(false); });
  if (m.deep_kind == Impl::DeepKind::kBeaufort) m.builder = std::thread([&m] { m.run_builder(); });
}

StreamingEngine::~StreamingEngine() {
  Impl& m = *impl_;
  {
    const std::lock_guard<std::mutex> lock(m.builder_mutex);
    m.builder_stop = true;
  }
  m.builder_cv.notify_all();
  if (m.builder.joinable()) m.builder.join();
  {
    const std::lock_guard<std::mutex> lock(m.mutex);
    m.stop = true;
  }
  m.work_cv.notify_all();
  if (m.harbour_worker.joinable()) m.harbour_worker.join();
  if (m.deep_worker.joinable()) m.deep_worker.join();
}

bool StreamingEngine::advance_to(double display_time_s) {
  Impl& m = *impl_;
  const double t = std::max(display_time_s, 0.0);
  const double steps = t / m.frame_interval_s;
  const long long k = static_cast<long long>(std::floor(steps));
  const double deep_steps = t / m.deep_interval_s;
  const long long j = static_cast<long long>(std::floor(deep_steps));
  // The previous snapshot: only this thread writes it, so it is read here without the lock.
  SurfaceSnapshot next = m.current;
  next.display_time_s = t;
  next.site = m.site;
  const bool has_deep = m.deep_kind != Impl::DeepKind::kNone;
  // Lockstep, or nothing shown yet (a sea never starts flat): what the rings lack is made here.
  const bool make_missing = m.options.lockstep || !m.current.harbour_from;
  bool missing_harbour = false, missing_deep = false;
  std::optional<PlanStep> shown_step;
  {
    const std::lock_guard<std::mutex> lock(m.mutex);
    m.schedule_locked(k, j, true);
    const HarbourEntry* from = m.harbour_ring.find(k);
    const HarbourEntry* to = m.harbour_ring.find(k + 1);
    if (from && to) {
      next.harbour_from = from->keyframe;
      next.harbour_to = to->keyframe;
      next.harbour_fraction = steps - static_cast<double>(k);
      shown_step = from->step;
    } else {
      missing_harbour = true;
      if (!make_missing) {
        ++m.counters.harbour_underruns;
        if (from) {  // show step k alone until k + 1 arrives
          next.harbour_from = next.harbour_to = from->keyframe;
          next.harbour_fraction = 0.0;
          shown_step = from->step;
        }  // else: hold the last pair shown
      }
    }
    if (!has_deep) {
      next.deep_from = next.deep_to = nullptr;
      next.deep_fraction = 0.0;
    } else {
      const DeepEntry* deep_from = m.deep_ring.find(j);
      const DeepEntry* deep_to = m.deep_ring.find(j + 1);
      if (deep_from && deep_to) {
        next.deep_from = deep_from->keyframe;
        next.deep_to = deep_to->keyframe;
        next.deep_fraction = deep_steps - static_cast<double>(j);
      } else {
        missing_deep = true;
        if (!make_missing) {
          ++m.counters.deep_underruns;
          if (deep_from) {
            next.deep_from = next.deep_to = deep_from->keyframe;
            next.deep_fraction = 0.0;
          }
        }
      }
    }
    if (!make_missing && (missing_harbour || missing_deep)) ++m.counters.underruns;
  }
  const bool planned = make_missing || !(missing_harbour || missing_deep);
  if (make_missing && (missing_harbour || missing_deep)) {
    // The slow path on this thread (snapshot_at's): exactly the keyframes of t.
    if (missing_harbour) next.harbour_from = next.harbour_to = nullptr;
    if (missing_deep) next.deep_from = next.deep_to = nullptr;
    const Impl::SlowResult made = m.make_synchronously(k, j, missing_harbour, missing_deep, next);
    m.count_slow(made);
    if (missing_harbour) {
      next.harbour_fraction = steps - static_cast<double>(k);
      const std::lock_guard<std::mutex> slow(m.slow_mutex);
      shown_step = m.slow_plan.step(k);
    }
    if (missing_deep) next.deep_fraction = deep_steps - static_cast<double>(j);
  }
  {
    const std::lock_guard<std::mutex> lock(m.mutex);
    if (shown_step) {
      m.counters.plan_step = shown_step->step;
      m.counters.transitions_taken = shown_step->transitions_taken;
      m.counters.in_crossfade = shown_step->in_crossfade;
    }
    m.counters.last_advance_planned = planned;
  }
  // Swap under the snapshot lock; the old snapshot's keyframes are let go after it (outside).
  {
    const std::lock_guard<std::mutex> lock(m.snapshot_mutex);
    std::swap(m.current, next);
  }
  return planned;
}

std::vector<std::shared_ptr<const HarbourKeyframe>> StreamingEngine::upcoming_harbour_keyframes(int count) const {
  const Impl& m = *impl_;
  const std::lock_guard<std::mutex> lock(m.mutex);
  return keyframes_after(m.harbour_ring.entries, m.current.harbour_to, count);  // the render thread writes current
}

std::vector<std::shared_ptr<const DeepWaterKeyframe>> StreamingEngine::upcoming_deep_keyframes(int count) const {
  const Impl& m = *impl_;
  const std::lock_guard<std::mutex> lock(m.mutex);
  return keyframes_after(m.deep_ring.entries, m.current.deep_to, count);
}

SurfaceSnapshot StreamingEngine::snapshot() const {
  const std::lock_guard<std::mutex> lock(impl_->snapshot_mutex);
  return impl_->current;
}

bool StreamingEngine::wait_until_ready(double display_time_s, std::chrono::milliseconds timeout) {
  Impl& m = *impl_;
  const double t = std::max(display_time_s, 0.0);
  const long long k = static_cast<long long>(std::floor(t / m.frame_interval_s));
  const long long j = static_cast<long long>(std::floor(t / m.deep_interval_s));
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::unique_lock<std::mutex> lock(m.mutex);
  while (true) {
    // Let go of what lies before t each time (the worker may have filled the ring with it), so the
    // worker has room for the keyframes t needs.
    m.schedule_locked(k, j, true);
    if (m.ready_locked(k, j)) return true;
    if (m.ready_cv.wait_until(lock, deadline) == std::cv_status::timeout) return m.ready_locked(k, j);
  }
}

bool StreamingEngine::wait_until_filled(std::chrono::milliseconds timeout) {
  Impl& m = *impl_;
  std::unique_lock<std::mutex> lock(m.mutex);
  return m.ready_cv.wait_for(lock, timeout, [&] {
    return m.harbour_ring.full() && (m.deep_kind == Impl::DeepKind::kNone || m.deep_ring.full());
  });
}

SurfaceSnapshot StreamingEngine::snapshot_at(double display_time_s) {
  Impl& m = *impl_;
  const double t = std::max(display_time_s, 0.0);
  const double steps = t / m.frame_interval_s;
  const long long k = static_cast<long long>(std::floor(steps));
  const double deep_steps = t / m.deep_interval_s;
  const long long j = static_cast<long long>(std::floor(deep_steps));
  SurfaceSnapshot result;
  result.display_time_s = t;
  result.site = m.site;
  result.harbour_fraction = steps - static_cast<double>(k);
  result.deep_fraction = m.deep_kind == Impl::DeepKind::kNone ? 0.0 : deep_steps - static_cast<double>(j);
  {
    const std::lock_guard<std::mutex> lock(m.mutex);
    if (const HarbourEntry* from = m.harbour_ring.find(k))
      if (const HarbourEntry* to = m.harbour_ring.find(k + 1)) {
        result.harbour_from = from->keyframe;
        result.harbour_to = to->keyframe;
      }
    if (m.deep_kind != Impl::DeepKind::kNone)
      if (const DeepEntry* from = m.deep_ring.find(j))
        if (const DeepEntry* to = m.deep_ring.find(j + 1)) {
          result.deep_from = from->keyframe;
          result.deep_to = to->keyframe;
        }
  }
  const bool need_harbour = !result.harbour_from;
  const bool need_deep = m.deep_kind != Impl::DeepKind::kNone && !result.deep_from;
  if (!need_harbour && !need_deep) return result;
  const Impl::SlowResult made = m.make_synchronously(k, j, need_harbour, need_deep, result);
  m.count_slow(made);
  return result;
}

StreamingStats StreamingEngine::stats() const {
  const Impl& m = *impl_;
  StreamingStats result;
  {
    const std::lock_guard<std::mutex> lock(m.mutex);
    result = m.counters;
    result.ring_fill = m.harbour_ring.fill();
    result.deep_ring_fill = m.deep_ring.fill();
  }
  result.harbour_keyframes_allocated = m.harbour_pool.allocated();
  result.deep_keyframes_allocated = m.deep_pool.allocated();
  return result;
}

std::string StreamingEngine::memory_summary() const {
  const Impl& m = *impl_;
  std::string text = fmt::format("harbour ring {} x {:.1f} MiB = {:.1f} MiB", m.harbour_ring.capacity,
                                 mebibytes(m.bytes_harbour), mebibytes(m.harbour_ring.capacity * m.bytes_harbour));
  if (m.deep_kind != Impl::DeepKind::kNone)
    text += fmt::format("; deep-water ring {} x {:.2f} MiB = {:.1f} MiB", m.deep_ring.capacity, mebibytes(m.bytes_deep),
                        mebibytes(m.deep_ring.capacity * m.bytes_deep));
  return text;
}

void StreamingEngine::set_beaufort(const BeaufortSea& sea) {
  Impl& m = *impl_;
  if (m.deep_kind != Impl::DeepKind::kBeaufort)
    throw Error(fmt::format("streaming engine for {}", m.folder.string()),
                m.deep_kind == Impl::DeepKind::kBake ? "shows the bake's own deep-water field, which the wind cannot change"
                                                     : "shows no deep water",
                "open the sequence with StreamingOptions::deep_water = DeepWaterChoice::kBeaufort");
  {
    const std::lock_guard<std::mutex> lock(m.builder_mutex);
    m.builder_request = sea;  // only the latest request matters
  }
  m.builder_cv.notify_one();
}

const sequence::SequenceManifest& StreamingEngine::manifest() const { return impl_->reader.manifest(); }
double StreamingEngine::frame_interval_s() const { return impl_->frame_interval_s; }
PlaybackPlan StreamingEngine::plan() const { return impl_->plan_template; }
bool StreamingEngine::deep_water_is_bakes() const { return impl_->deep_kind == Impl::DeepKind::kBake; }
std::shared_ptr<const DeepWaterInsideLayer> StreamingEngine::deep_water_inside_layer() const { return impl_->inside_layer; }
const std::optional<SpectrumSplitRecord>& StreamingEngine::spectrum_split() const { return impl_->split; }

}  // namespace nearshore::runtime
