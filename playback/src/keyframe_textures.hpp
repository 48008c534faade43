#pragma once
// The GPU copies of a snapshot's keyframes (private to the renderer). Each harbour and deep-water
// keyframe is uploaded once, by serial, into a small pool of texture slots. A keyframe the engine
// says is coming (stage) is uploaded in row chunks within a byte budget per drawn frame, so a
// 1024 x 1024 keyframe (12 MB: eta, its rate and breaking as R32F; then its slope moments' mip
// levels, 16 bytes a cell and a third more, in rows too) spreads over several frames instead of
// stalling one; a keyframe a snapshot needs before it is complete is finished at once (counted
// as forced). A staged harbour keyframe's slope moments are computed on a worker thread from
// stage() on (std::async: slope_moment_pyramid is a pure function of eta), so the thread that draws
// only sends them; it waits for them only if its upload reaches them before the worker is done.
// Needs a current OpenGL context (stage() needs none).
#include <glad/gl.h>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <future>
#include <memory>
#include <utility>
#include <vector>

#include "nearshore/playback/slope_moments.hpp"
#include "nearshore/runtime/surface_snapshot.hpp"

namespace nearshore::playback {

struct UploadCounters {
  std::size_t bytes = 0;         ///< texture bytes sent
  std::size_t forced_bytes = 0;  ///< of which for keyframes a snapshot needed unfinished
};

/// The deep-water fields a vertex or fragment shader reads, one R32F array per field.
enum DeepField { kDeepEta, kDeepDx, kDeepDy, kDeepSlopeX, kDeepSlopeY, kDeepFieldCount };
/// A harbour keyframe's textures: surface elevation, breaking, d eta / dt (R32F, the grid's size),
/// and the slope moments (RGBA32F, mip-mapped: slope_moments.hpp) in the fourth texture.
inline constexpr int kHarbourFieldCount = 3;
inline constexpr int kSlopeMomentsTexture = kHarbourFieldCount;
static_assert(kSlopeMomentsTexture < kDeepFieldCount, "a slot's texture array holds either kind");

class KeyframeTextures {
 public:
  KeyframeTextures(int harbour_slot_count, int deep_slot_count);
  ~KeyframeTextures();
  KeyframeTextures(const KeyframeTextures&) = delete;
  KeyframeTextures& operator=(const KeyframeTextures&) = delete;

  /// Queues a keyframe for a budgeted upload. false when the queue is full (slots - 2 entries:
  /// two slots stay for the pair on screen) or the keyframe is already resident or queued.
  bool stage(std::shared_ptr<const runtime::HarbourKeyframe> keyframe);
  bool stage(std::shared_ptr<const runtime::DeepWaterKeyframe> keyframe);

  /// What a draw binds: the textures of the snapshot's pair (from, to), resident after prepare().
  struct Bound {
    GLuint harbour_eta[2] = {0, 0}, harbour_breaking[2] = {0, 0};
    GLuint harbour_eta_rate[2] = {0, 0};  ///< d eta / dt (zeros where a keyframe has none; used when
                                          ///< runtime::harbour_joined_by_hermite)
    GLuint harbour_slope_moments[2] = {0, 0};  ///< RGBA32F mip pyramid (slope_moments.hpp)
    GLuint deep[kDeepFieldCount][2] = {};
    int deep_size = 0, cascade_count = 0;  ///< cascade_count: the field's cascades (layers 0 .. count - 1)
    /// The split's inside layer (runtime/surface_snapshot.hpp): bit c of the mask draws the
    /// field's cascade c inside the harbour rectangle; layers cascade_count .. + inside_layer_count
    /// - 1 are the band-limited cascades drawn only there.
    int inside_layer_count = 0;
    std::uint32_t inside_cascade_mask = 0;
    std::vector<float> tile_lengths_m;  ///< per layer (the field's cascades, then the inside ones)
  };
  /// Makes the snapshot's keyframes resident (finishing any that are not: forced), then spends
  /// `budget_bytes` on the staged queue (at least one row, so a queue always advances).
  Bound prepare(const runtime::SurfaceSnapshot& snapshot, std::size_t budget_bytes, UploadCounters& counters);

 private:
  struct Slot {
    std::uint64_t serial = 0;  // 0: free
    bool complete = false;
    long long last_used = -1;
    long long rows_done = 0, rows_total = 0;  // progress in rows of one field (of one layer)
    GLuint textures[kDeepFieldCount] = {};
    int width = 0, height = 0, layers = 0;
    std::vector<SlopeMomentLevel> moments;                    // held until sent
    std::future<std::vector<SlopeMomentLevel>> moments_pending;  // the worker's, until the upload needs them
    std::shared_ptr<const runtime::HarbourKeyframe> harbour;  // held until complete
    std::shared_ptr<const runtime::DeepWaterKeyframe> deep;
  };
  Slot* find(std::vector<Slot>& slots, std::uint64_t serial);
  Slot& claim(std::vector<Slot>& slots, std::uint64_t serial, std::uint64_t pinned_a, std::uint64_t pinned_b);
  void start_harbour(Slot& slot, std::shared_ptr<const runtime::HarbourKeyframe> keyframe);
  void start_deep(Slot& slot, std::shared_ptr<const runtime::DeepWaterKeyframe> keyframe);
  std::size_t upload_rows(Slot& slot, std::size_t budget_bytes);  // returns the bytes sent
  Slot& resident_harbour(const std::shared_ptr<const runtime::HarbourKeyframe>& keyframe, std::uint64_t other,
                         UploadCounters& counters);
  Slot& resident_deep(const std::shared_ptr<const runtime::DeepWaterKeyframe>& keyframe, std::uint64_t other,
                      UploadCounters& counters);

  std::vector<Slot> harbour_slots_, deep_slots_;
  std::deque<std::shared_ptr<const runtime::HarbourKeyframe>> harbour_queue_;
  std::deque<std::shared_ptr<const runtime::DeepWaterKeyframe>> deep_queue_;
  // The slope moments the workers compute for staged harbour keyframes (by serial), taken by
  // start_harbour; a keyframe needed unstaged computes its own on the render thread.
  std::vector<std::pair<std::uint64_t, std::future<std::vector<SlopeMomentLevel>>>> moments_computing_;
  // The last sent pyramid's storage, for the next one start_harbour computes itself: a keyframe
  // needed unstaged then writes into memory already touched (one pyramid held: 21 bytes a cell).
  std::vector<SlopeMomentLevel> spare_moments_;
  std::vector<float> zero_row_;
  long long frame_ = 0;
  std::uint64_t pinned_harbour_[2] = {0, 0}, pinned_deep_[2] = {0, 0};
};

}  // namespace nearshore::playback
