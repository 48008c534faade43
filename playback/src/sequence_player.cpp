#include "nearshore/playback/sequence_player.hpp"

#include <cmath>
#include <numeric>
#include <string>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {

namespace {
sequence::LoopSchedule plain_schedule(const sequence::SequenceReader& reader,
                                      const std::vector<int>& frame_order) {
  sequence::LoopSchedule schedule;
  schedule.kind = "frame order";
  if (frame_order.empty())
    for (int frame = 0; frame < reader.frame_count(); ++frame) schedule.shown.push_back({frame, frame, 0.0});
  else
    for (int frame : frame_order) schedule.shown.push_back({frame, frame, 0.0});
  schedule.length_s = static_cast<double>(schedule.shown.size()) * reader.frame_interval_s();
  return schedule;
}
}  // namespace

SequencePlayer::SequencePlayer(const sequence::SequenceReader& reader, std::vector<int> frame_order)
    : SequencePlayer(reader, plain_schedule(reader, frame_order)) {}

SequencePlayer::SequencePlayer(const sequence::SequenceReader& reader, sequence::LoopSchedule schedule)
    : reader_(reader), schedule_(std::move(schedule)), order_(schedule_.frames()) {
  if (reader_.frame_count() < 1)
    throw Error(reader_.folder().string(), "has no frames", "bake it again with a longer duration");
  if (schedule_.shown.empty())
    throw Error(reader_.folder().string(), "the loop to play has no frames",
                "rebuild the loop tables with `nearshore loops`");
  for (const sequence::BlendSource& step : schedule_.shown)
    for (int index : {step.source_frame, step.target_frame})
      if (index < 0 || index >= reader_.frame_count())
        throw Error(reader_.folder().string(),
                    "the loop to play names frame " + std::to_string(index) + " but the sequence has " +
                        std::to_string(reader_.frame_count()),
                    "rebuild the loop tables with `nearshore loops`");
  advance_to(0.0);
}

sequence::Frame SequencePlayer::shown_frame(int position) const {
  const sequence::BlendSource& step = schedule_.shown[static_cast<std::size_t>(position)];
  sequence::Frame source = reader_.read_frame(step.source_frame, sequence::ChannelSelection::display());
  if (step.target_weight <= 0.0) return source;
  // A crossfade step: the same weight for every channel, so the shown water volume is the
  // weighted volume of the two frames (loop_playback.hpp).
  const sequence::Frame target = reader_.read_frame(step.target_frame, sequence::ChannelSelection::display());
  sequence::Frame blended;
  sequence::blend_frames(source, target, step.target_weight, blended);
  return blended;
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
    current_ = shown_frame(position);
    next_ = shown_frame(next_position);
  }
  // Decode the frame after next while this pair is on screen.
  prefetch_position_ = next_position;
  const int ahead = (next_position + 1) % count;
  prefetch_ = std::async(std::launch::async, [this, ahead] { return shown_frame(ahead); });
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
    for (std::size_t i = 0; i < a.size(); ++i)
      out.values()[i] = (1.f - w) * a.values()[i] + w * b.values()[i];
  };
  blend(current_.surface_elevation_m, next_.surface_elevation_m, blended_.surface_elevation_m);
  blend(current_.breaking, next_.breaking, blended_.breaking);
}

}  // namespace nearshore::playback
