#pragma once
// Playing a harbour's sea-state library (`nearshore library`, sequence/library_index.hpp): the
// state nearest the conditions asked for streams like any sequence (a StreamingEngine); when the
// conditions change during an exercise (the wind veering, the tide rising) the player crossfades
// from the state on screen to the new one over a given span of display time.
//
// During a crossfade both states stream, and the snapshot shown is their blend with weight
// w(t) = smoothstep((t - t0) / T) of the new state:
//   harbour  = (1 - w) H_old(p, t) + w H_new(p, t)       (each first interpolated in time as drawn)
//   deep     = (1 - w) sum_c D_old,c + w sum_c D_new,c   (the two states' cascades side by side,
//                                                          each scaled by its weight)
// a snapshot of the same form as one state's (surface_snapshot.hpp), so the renderer draws it and
// the CPU queries sample it unchanged. Two uncorrelated seas blended this way keep
// (1 - w)^2 + w^2 of their variance (half at mid-fade), as the index's selection rule says; the
// smoothstep keeps that dip short. The harbour site (depth, land) is the new state's from the
// first frame of the fade: states of one library share the grid, and a tide state differs only
// by its still-water level, which the fade then shows as a change of depth at once.
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "nearshore/runtime/streaming_engine.hpp"
#include "nearshore/sequence/library_index.hpp"

namespace nearshore::runtime {

class LibraryPlayer {
 public:
  /// Reads `library_folder`/library.json and starts streaming the baked state nearest
  /// `conditions` (select_library_states). Throws nearshore::Error naming the index for a library
  /// with no baked state, and whatever StreamingEngine throws for that state's folder.
  LibraryPlayer(const std::filesystem::path& library_folder, const sequence::SeaConditions& conditions,
                StreamingOptions options = {});
  ~LibraryPlayer();
  LibraryPlayer(const LibraryPlayer&) = delete;
  LibraryPlayer& operator=(const LibraryPlayer&) = delete;

  /// Moves to the baked state nearest `conditions`, crossfading over `crossfade_s` of display time
  /// from the next advance_to (0: a cut). Nothing changes when it is the state on screen. A
  /// request during a crossfade finishes that one at once and starts the new one. Returns the id
  /// of the state now on its way to the screen. Render thread.
  const std::string& request(const sequence::SeaConditions& conditions, double crossfade_s);

  /// As StreamingEngine::advance_to, for the state(s) on screen. Render thread. True when every
  /// state shown showed its planned keyframes (no underrun).
  bool advance_to(double display_time_s);
  /// The snapshot of the last advance_to: one state's, or the crossfade's blend. Any thread.
  SurfaceSnapshot snapshot() const;
  /// As StreamingEngine::wait_until_ready, for every state that `display_time_s` shows: the one on
  /// screen and, during a crossfade, the one fading out (whose frames may lag the new one's
  /// otherwise, and the blend then holds its latest frame). For a host's start-up, a recording that
  /// must be frame-exact, and tests; never for the render loop. Render thread.
  bool wait_until_ready(double display_time_s, std::chrono::milliseconds timeout);

  /// The engine of the state on screen (the new one during a crossfade).
  StreamingEngine& engine();
  const StreamingEngine& engine() const;
  const std::string& state_id() const;
  /// w of the new state in a crossfade on screen, 1 when none is.
  double crossfade_weight() const;
  const sequence::LibraryIndex& index() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What a viewer or a host plays: one baked sequence, or a sea-state library (a folder holding
/// library.json) with its crossfades, behind one interface.
class PlayedSea {
 public:
  /// `folder` with library.json: a LibraryPlayer started at the state nearest `conditions`;
  /// otherwise a StreamingEngine on the sequence (`conditions` unused). Throws what they throw.
  PlayedSea(const std::filesystem::path& folder, const sequence::SeaConditions& conditions, StreamingOptions options);

  /// The engine on screen (the new state's during a crossfade).
  StreamingEngine& engine() const { return library_ ? library_->engine() : *single_; }
  /// The library, or null for one sequence.
  LibraryPlayer* library() const { return library_.get(); }
  /// True when the planned keyframes are shown (StreamingEngine::advance_to).
  bool advance_to(double display_time_s) {
    return library_ ? library_->advance_to(display_time_s) : single_->advance_to(display_time_s);
  }
  SurfaceSnapshot snapshot() const { return library_ ? library_->snapshot() : single_->snapshot(); }
  /// Every state on screen ready for `display_time_s` (LibraryPlayer::wait_until_ready).
  bool wait_until_ready(double display_time_s, std::chrono::milliseconds timeout) {
    return library_ ? library_->wait_until_ready(display_time_s, timeout) : single_->wait_until_ready(display_time_s, timeout);
  }

 private:
  std::unique_ptr<StreamingEngine> single_;
  std::unique_ptr<LibraryPlayer> library_;
};

}  // namespace nearshore::runtime
