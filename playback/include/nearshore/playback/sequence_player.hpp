#pragma once
// SequencePlayer: streams a baked sequence to the renderer at playback time t. It plays a loop
// schedule forever (sequence/loop_playback.hpp: the loop `nearshore loops` planned, read from the
// sequence folder's loops.json, with its crossfades), or a plain frame order; between two steps
// the fields are blended linearly in time, so the picture moves smoothly at any display rate. The
// next step (one frame, or the two frames of a crossfade blend) is decoded on a background thread
// while the current pair is shown.
#include <future>
#include <vector>

#include "nearshore/sequence/loop_playback.hpp"
#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::playback {

class SequencePlayer {
 public:
  /// `frame_order`: indices into the sequence, played in order and then from the start again.
  /// Empty means 0, 1, ..., frame_count - 1. Throws nearshore::Error for an index out of range.
  SequencePlayer(const sequence::SequenceReader& reader, std::vector<int> frame_order = {});
  /// Plays `schedule` (e.g. sequence::read_loop_schedule(folder)), crossfade blends included.
  SequencePlayer(const sequence::SequenceReader& reader, sequence::LoopSchedule schedule);
  ~SequencePlayer();

  /// Advances to playback time `time_s` (seconds since start, any value >= the last one) and
  /// returns the blended surface elevation (m) and breaking indicator.
  void advance_to(double time_s);
  const Raster<float>& surface_elevation_m() const { return blended_.surface_elevation_m; }
  const Raster<float>& breaking() const { return blended_.breaking; }
  /// Position in the order (which step and the blend fraction to the next) at the last advance.
  int order_position() const { return position_; }
  double blend_fraction() const { return fraction_; }
  const std::vector<int>& frame_order() const { return order_; }
  const sequence::LoopSchedule& schedule() const { return schedule_; }

 private:
  void load_pair(int position);
  sequence::Frame shown_frame(int position) const;  // decodes (and blends) step `position`
  const sequence::SequenceReader& reader_;
  sequence::LoopSchedule schedule_;
  std::vector<int> order_;  // schedule_.frames()
  sequence::Frame current_, next_, blended_;
  std::future<sequence::Frame> prefetch_;
  int position_ = -1, prefetch_position_ = -1;
  double fraction_ = 0;
};

}  // namespace nearshore::playback
