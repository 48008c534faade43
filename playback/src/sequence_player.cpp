#include "nearshore/playback/sequence_player.hpp"

#include <cmath>
#include <numeric>
#include <string>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {

SequencePlayer::SequencePlayer(const sequence::SequenceReader& reader, std::vector<int> frame_order)
    : reader_(reader), order_(std::move(frame_order)) {
  if (reader_.frame_count() < 1)
    throw Error(reader_.folder().string(), "has no frames", "bake it again with a longer duration");
  if (order_.empty()) {
    order_.resize(reader_.frame_count());
    std::iota(order_.begin(), order_.end(), 0);
  }
  for (int index : order_)
    if (index < 0 || index >= reader_.frame_count())
      throw Error(reader_.folder().string(),
                  "the frame order names frame " + std::to_string(index) + " but the sequence has " +
                      std::to_string(reader_.frame_count()),
                  "rebuild the loop tables with `nearshore loops`");
  advance_to(0.0);
}

SequencePlayer::~SequencePlayer() {
  if (prefetch_.valid()) prefetch_.wait();
}

void SequencePlayer::load_pair(int position) {
  const int count = static_cast<int>(order_.size());
  const int next_position = (position + 1) % count;
  if (position == prefetch_position_ && prefetch_.valid()) {
    // The frame decoded in the background becomes the current one.
    current_ = std::move(next_);
    next_ = prefetch_.get();
  } else {
    if (prefetch_.valid()) prefetch_.wait();
    current_ = reader_.read_frame(order_[position], sequence::ChannelSelection::display());
    next_ = reader_.read_frame(order_[next_position], sequence::ChannelSelection::display());
  }
  // Decode the frame after next while this pair is on screen.
  prefetch_position_ = next_position;
  const int ahead = order_[(next_position + 1) % count];
  prefetch_ = std::async(std::launch::async, [this, ahead] {
    return reader_.read_frame(ahead, sequence::ChannelSelection::display());
  });
  position_ = position;
}

void SequencePlayer::advance_to(double time_s) {
  const double steps = std::max(time_s, 0.0) / reader_.frame_interval_s();
  const long whole = static_cast<long>(std::floor(steps));
  const int position = static_cast<int>(whole % static_cast<long>(order_.size()));
  fraction_ = steps - whole;
  if (position != position_) {
    // Normally one step on (use the prefetched frame); after a jump, decode afresh.
    if (position_ >= 0 && position == (position_ + 1) % static_cast<int>(order_.size()))
      load_pair(position);
    else {
      prefetch_position_ = -1;
      load_pair(position);
    }
  }
  const auto blend = [this](const Raster<float>& a, const Raster<float>& b, Raster<float>& out) {
    if (out.columns() != a.columns() || out.rows() != a.rows()) out = Raster<float>(a.columns(), a.rows());
    const float w = static_cast<float>(fraction_);
    for (std::size_t i = 0; i < a.size(); ++i) out.values()[i] = (1.f - w) * a.values()[i] + w * b.values()[i];
  };
  blend(current_.surface_elevation_m, next_.surface_elevation_m, blended_.surface_elevation_m);
  blend(current_.breaking, next_.breaking, blended_.breaking);
}

}  // namespace nearshore::playback
