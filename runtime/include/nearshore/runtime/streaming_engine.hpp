#pragma once
// The streaming engine: plays a baked sequence folder endlessly by a playback plan, decoding
// ahead on background threads into bounded rings of keyframes, and fills a SurfaceSnapshot per
// displayed frame without ever waiting on disk (docs/runtime.md).
//
//   harbour worker thread                           render thread (the host's)
//   plan step k -> read frames (+ crossfade blend)  advance_to(t): k = floor(t / dt), f = t/dt - k;
//     -> HarbourKeyframe k  --> harbour ring -->      pick keyframes k, k + 1 and deep j, j + 1
//   deep-water worker thread                        snapshot(): the SurfaceSnapshot (shared_ptrs)
//   display time j * interval -> bake times
//     -> one weighted FFT -> DeepWaterKeyframe j --> deep ring -->
//
// Each worker sleeps while its ring is full (decoding and the FFTs run on two cores at once).
// Keyframes are recycled through a pool once no ring and no snapshot holds them, so memory is
// bounded by the rings (plus what the host keeps in snapshots) whatever the sequence length, and
// steady play allocates nothing.
//
// Time: display time 0 is plan step 0; harbour step k is shown over [k dt, (k + 1) dt) with dt
// the manifest's frame_interval_s, interpolated linearly to step k + 1 (seed 003 section 3:
// trilinear sampling of the vertex textures, bilinear in space and linear in time). Hosts scale
// time themselves (pass 0.5 t for half speed).
//
// Two ways for the host's clock (StreamingOptions::lockstep):
//  - free-running (default): advance_to never waits; a keyframe the workers have not made yet is
//    an underrun (counted, and advance_to returns false), the nearest keyframes are held. Only
//    the very first advance_to makes what it lacks on the calling thread, so a sea never starts
//    flat: the first displayed frame is always the planned one.
//  - lockstep: the host's clock drives everything. advance_to shows exactly the keyframes of the
//    requested time: from the rings when the workers got there, else decoded and synthesised on
//    the calling thread (the slow path of snapshot_at). Any time rate, pausing, stepping and going
//    back give the fields real time gives at the same display times, bit for bit (the keyframes
//    of a time are a pure function of the sequence, plan, seed and field: no history enters).
//
// Threads: advance_to and snapshot_at are for one thread at a time (the render thread);
// snapshot(), stats(), site() and set_beaufort() may be called from any thread. The only lock the
// render thread takes is held by the worker for pointer moves, never across decoding or I/O.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nearshore/runtime/deep_water_source.hpp"
#include "nearshore/runtime/playback_plan.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::runtime {

/// Which sea beyond the harbour.
enum class DeepWaterChoice {
  kBakeElseBeaufort,  ///< the bake's own [deep_water] field when it has one, else the Beaufort sea
  kBeaufort,          ///< the Beaufort sea of StreamingOptions::beaufort always
  kNone,              ///< none: a flat sea beyond the harbour (snapshots carry no deep keyframes)
};

struct StreamingOptions {
  PlanKind plan = PlanKind::kOptimalLoop;
  std::optional<std::uint64_t> seed;   ///< random walk: replaces loops.json's random_walk.seed
  /// Harbour keyframes held (the one shown, the next, and those decoded ahead). 0: automatic,
  /// ring_lookahead_s of play + 2, within [4, 64], reduced until the ring fits max_ring_bytes
  /// (at least 3). Each keyframe is 4 channels x columns x rows floats (16 MiB at 1024 x 1024).
  int ring_capacity = 0;
  /// Deep-water keyframes held. 0: automatic, the harbour ring's span of time + 2, within [4, 256].
  int deep_water_ring_capacity = 0;
  double ring_lookahead_s = 1.0;
  std::size_t max_ring_bytes = std::size_t{512} << 20;
  /// The deep-water ring's own bound. Its keyframes come every 1/30 s: at 3 x 256^2 cascades
  /// (9 MiB each: 7.5 of channels, 1.5 of the CPU queries' QueryTile) the harbour ring's span
  /// would hold 60 of them; 128 MiB keeps 14, about half a second.
  std::size_t max_deep_ring_bytes = std::size_t{128} << 20;
  double deep_water_interval_s = 1.0 / 30.0;  ///< deep keyframes at display times j * interval
  sequence::Verify verify = sequence::Verify::kNo;  ///< check each frame's XXH64 as it is read
  DeepWaterChoice deep_water = DeepWaterChoice::kBakeElseBeaufort;
  BeaufortSea beaufort;                ///< the Beaufort sea (force 3 by default)
  double edge_fade_m = -1.0;           ///< < 0: automatic (harbour_site.hpp)
  /// The host's clock drives everything (see the top of this header): advance_to makes what the
  /// rings lack on the calling thread instead of holding the last keyframes. For simulators that
  /// run faster or slower than real time, pause, step or rewind, and for recordings.
  bool lockstep = false;
  /// Test hook, called on the harbour worker thread before it decodes step k (e.g. to hold it
  /// back and provoke an underrun deterministically). Must not call back into the engine.
  std::function<void(long long step)> before_decode;
};

struct StreamingStats {
  int ring_fill = 0, ring_capacity = 0;            ///< harbour keyframes held / capacity
  int deep_ring_fill = 0, deep_ring_capacity = 0;  ///< deep-water keyframes held / capacity
  std::size_t harbour_keyframe_bytes = 0, deep_keyframe_bytes = 0;
  long long harbour_keyframes_allocated = 0;       ///< alive now (rings + snapshots + the worker's)
  long long deep_keyframes_allocated = 0;
  long long underruns = 0;          ///< advance_to calls that could not show the planned keyframes
  long long harbour_underruns = 0, deep_underruns = 0;
  /// Keyframes made on the calling thread (lockstep, the first advance, snapshot_at's slow path).
  long long synchronous_keyframes = 0;
  bool last_advance_planned = true;  ///< the last advance_to showed the planned keyframes
  long long keyframes_decoded = 0;  ///< harbour keyframes made (held ones included)
  long long deep_keyframes_synthesised = 0;
  double decode_seconds = 0.0;      ///< wall time of harbour decoding (read + blend) on its worker thread
  double decode_cpu_seconds = 0.0;  ///< its CPU time (meaningful on a shared machine)
  double deep_seconds = 0.0, deep_cpu_seconds = 0.0;  ///< the same for the deep-water synthesis
  long long bad_frames_held = 0;    ///< frames that failed to read and were replaced by the last good one
  long long plan_step = 0;          ///< the step shown by the last advance_to
  long long transitions_taken = 0;  ///< jumps of the plan landed by that step
  bool in_crossfade = false;
  std::string plan;                 ///< the plan followed (PlaybackPlan::description), fallback included
  std::string last_message;         ///< the last problem (fallback to frame order, a bad frame); empty if none
  double frame_interval_s = 0.0;
  /// Harbour keyframes per second of decoding, and as a multiple of real time (1 / dt frames/s).
  double decode_frames_per_s() const { return decode_seconds > 0 ? keyframes_decoded / decode_seconds : 0.0; }
  double decode_real_time_multiple() const { return decode_frames_per_s() * frame_interval_s; }
};

/// The display times a sea's timeline accepts (s): finite, from 0 (the first step of its plan) to
/// 1e9 s (32 years: past it a double keeps under a microsecond of the fraction between frames,
/// and no exercise runs that long). The one rule the public faces (the C API, Python) check a
/// host's time against before it reaches an engine.
inline constexpr double kLatestDisplayTime_s = 1e9;
inline bool is_display_time(double display_time_s) {
  return std::isfinite(display_time_s) && display_time_s >= 0.0 && display_time_s <= kLatestDisplayTime_s;
}

class StreamingEngine {
 public:
  /// Opens `folder` (manifest, depth.exr, the deep-water field, the plan) and starts the worker.
  /// Throws nearshore::Error for a missing, unreadable or newer-version manifest, an unreadable
  /// depth.exr or deep-water coefficient file. A plan that cannot be made (no, bad or foreign
  /// loops.json; no period loop) is NOT an error: the engine plays the frames in order and says
  /// why in stats().last_message.
  explicit StreamingEngine(const std::filesystem::path& folder, StreamingOptions options = {});
  ~StreamingEngine();
  StreamingEngine(const StreamingEngine&) = delete;
  StreamingEngine& operator=(const StreamingEngine&) = delete;

  /// Moves the display to `display_time_s` (>= 0; s since plan step 0). Never waits on disk or
  /// on the worker: it takes keyframes k, k + 1 (harbour) and j, j + 1 (deep water) from the
  /// rings; one that is not there yet is an underrun: the engine shows keyframe k alone if it has
  /// it, else holds the last pair shown, and counts it. A time behind the rings or far ahead of
  /// the worker makes the worker restart there (a seek: underruns until it catches up). Going
  /// back (an instructor's rewind) is a seek like any other. Exceptions: with
  /// StreamingOptions::lockstep, and on the first call, what the rings lack is made on the
  /// calling thread instead (that call then waits on disk and the FFTs). Returns true when the
  /// snapshot shows the planned keyframes of `display_time_s`, false after an underrun.
  bool advance_to(double display_time_s);
  /// The snapshot of the last advance_to (cheap: shared_ptr copies). Any thread.
  SurfaceSnapshot snapshot() const;
  /// The snapshot at any display time: from the rings when they hold the keyframes needed (no
  /// waiting), else decoded and synthesised synchronously on the caller's thread (slow path:
  /// one or two frame reads and one FFT set, milliseconds to tens of milliseconds; serialised
  /// between callers). Does not move the display. Any thread.
  SurfaceSnapshot snapshot_at(double display_time_s);
  /// Waits until the keyframes for `display_time_s` are in the rings, at most `timeout`: for a
  /// host's start-up (and tests), never for the render loop. True when they are.
  bool wait_until_ready(double display_time_s, std::chrono::milliseconds timeout);
  /// Waits until both rings are full, at most `timeout`: a host's start-up before it starts its
  /// clock, so the rings' whole lookahead covers the first stalls (measured in the soak: starting
  /// the clock with two keyframes decoded underran for the first 2 s at 3 x real time).
  bool wait_until_filled(std::chrono::milliseconds timeout);

  StreamingStats stats() const;
  /// Up to `count` keyframes already decoded beyond the pair of the last advance_to, soonest
  /// first: a renderer stages them for a budgeted upload before they are needed
  /// (playback::WaterRenderer::stage). Never waits; the render thread.
  std::vector<std::shared_ptr<const HarbourKeyframe>> upcoming_harbour_keyframes(int count) const;
  std::vector<std::shared_ptr<const DeepWaterKeyframe>> upcoming_deep_keyframes(int count) const;
  /// "harbour ring 12 x 16.0 MiB = 192.0 MiB; deep-water ring 38 x 1.9 MiB = 72.0 MiB".
  std::string memory_summary() const;

  /// Changes the Beaufort sea (wind force and direction, ...). The new field is built on a
  /// builder thread and swapped in by the worker when ready: no stall; keyframes already in the
  /// deep ring keep the old sea (under a second of it). Throws nearshore::Error if the engine shows
  /// the bake's own field (DeepWaterChoice::kBakeElseBeaufort with a bake that has one) or none.
  void set_beaufort(const BeaufortSea& sea);

  std::shared_ptr<const HarbourSite> site() const { return site_; }
  const sequence::SequenceManifest& manifest() const;
  double frame_interval_s() const;
  /// The plan followed (a copy; PlanKind::kFrameOrder after a fallback).
  PlaybackPlan plan() const;
  /// True when the deep water is the bake's own field (coherent with the frames).
  bool deep_water_is_bakes() const;
  /// The split (issue 14 item 1, docs/runtime.md "The split"): when the bake left part of its
  /// spectrum to the deep-water layer (manifest wave_conditions.spectrum_split) and the engine
  /// shows the bake's own field, the layer every deep keyframe carries for inside the harbour
  /// rectangle (DeepWaterKeyframe::inside_cascade_mask, inside_cascades); else null.
  std::shared_ptr<const DeepWaterInsideLayer> deep_water_inside_layer() const;
  /// The manifest's split record (nullopt: the bake split nothing).
  const std::optional<SpectrumSplitRecord>& spectrum_split() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::shared_ptr<const HarbourSite> site_;
};

}  // namespace nearshore::runtime
