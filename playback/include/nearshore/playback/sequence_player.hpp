#pragma once
// SequencePlayer: streams a baked sequence to the renderer at playback time t. Frames follow a
// frame order (the loop plan of `nearshore loops`, or 0..n-1 for a periodic bake) that repeats
// forever; between two frames of the order the fields are blended linearly in time, so the picture
// moves smoothly at any display rate. The next frame is decoded on a background thread while the
// current pair is shown.
#include <future>
#include <vector>

#include "nearshore/sequence/sequence_reader.hpp"

namespace nearshore::playback {

class SequencePlayer {
 public:
  /// `frame_order`: indices into the sequence, played in order and then from the start again.
  /// Empty means 0, 1, ..., frame_count - 1. Throws nearshore::Error for an index out of range.
  SequencePlayer(const sequence::SequenceReader& reader, std::vector<int> frame_order = {});
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

 private:
  void load_pair(int position);
  const sequence::SequenceReader& reader_;
  std::vector<int> order_;
  sequence::Frame current_, next_, blended_;
  std::future<sequence::Frame> prefetch_;
  int position_ = -1, prefetch_position_ = -1;
  double fraction_ = 0;
};

}  // namespace nearshore::playback
