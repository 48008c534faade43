#include "keyframe_textures.hpp"
#include "gl_texture.hpp"

#include <algorithm>
#include <future>
#include <limits>
#include <utility>
#include <string>
#include <system_error>

#include "nearshore/core/error.hpp"

namespace nearshore::playback {

namespace {
constexpr std::size_t kUnlimited = std::numeric_limits<std::size_t>::max();

GLuint new_texture(GLenum target) {
  // Linear for the fragment shader's slopes and foam; the vertex path fetches texels itself.
  const GLint wrap = target == GL_TEXTURE_2D_ARRAY ? GL_REPEAT : GL_CLAMP_TO_EDGE;  // deep tiles are periodic
  return playback::new_texture(target, GL_LINEAR, wrap);
}

const std::vector<float>& deep_field(const ocean::DeepWaterFrame& frame, int field) {
  switch (field) {
    case kDeepEta: return frame.surface_elevation_m;
    case kDeepDx: return frame.displacement_x_m;
    case kDeepDy: return frame.displacement_y_m;
    case kDeepSlopeX: return frame.slope_x;
    default: return frame.slope_y;
  }
}

// Layer `layer` of a deep keyframe's texture arrays: the field's cascades, then the split's
// band-limited inside cascades (runtime/surface_snapshot.hpp; issue 14 item 1).
int deep_layer_count(const runtime::DeepWaterKeyframe& keyframe) {
  return static_cast<int>(keyframe.cascades.size() + keyframe.inside_cascades.size());
}
const ocean::DeepWaterFrame& deep_layer(const runtime::DeepWaterKeyframe& keyframe, int layer) {
  const std::size_t field_layers = keyframe.cascades.size();
  return std::size_t(layer) < field_layers ? keyframe.cascades[std::size_t(layer)]
                                           : keyframe.inside_cascades[std::size_t(layer) - field_layers];
}
}  // namespace

KeyframeTextures::KeyframeTextures(int harbour_slot_count, int deep_slot_count)
    : harbour_slots_(std::size_t(std::max(harbour_slot_count, 2))), deep_slots_(std::size_t(std::max(deep_slot_count, 2))) {}

KeyframeTextures::~KeyframeTextures() {
  for (auto* slots : {&harbour_slots_, &deep_slots_})
    for (Slot& slot : *slots)
      for (GLuint& texture : slot.textures)
        if (texture) glDeleteTextures(1, &texture);
}

bool KeyframeTextures::stage(std::shared_ptr<const runtime::HarbourKeyframe> keyframe) {
  if (!keyframe || harbour_queue_.size() + 2 >= harbour_slots_.size()) return false;
  if (Slot* slot = find(harbour_slots_, keyframe->serial); slot && slot->complete) return false;
  for (const auto& queued : harbour_queue_)
    if (queued->serial == keyframe->serial) return false;
  // The slope moments now, on a worker: by the time the upload has sent the three fields (and
  // whatever is queued before), they are ready, and the render thread only sends them.
  // Without a thread to spare (std::system_error), start_harbour computes them itself.
  try {
    moments_computing_.emplace_back(keyframe->serial, std::async(std::launch::async, [keyframe] {
                                      return slope_moment_pyramid(keyframe->surface_elevation_m);
                                    }));
  } catch (const std::system_error&) {
  }
  harbour_queue_.push_back(std::move(keyframe));
  return true;
}

bool KeyframeTextures::stage(std::shared_ptr<const runtime::DeepWaterKeyframe> keyframe) {
  if (!keyframe || deep_queue_.size() + 2 >= deep_slots_.size()) return false;
  if (Slot* slot = find(deep_slots_, keyframe->serial); slot && slot->complete) return false;
  for (const auto& queued : deep_queue_)
    if (queued->serial == keyframe->serial) return false;
  deep_queue_.push_back(std::move(keyframe));
  return true;
}

KeyframeTextures::Slot* KeyframeTextures::find(std::vector<Slot>& slots, std::uint64_t serial) {
  for (Slot& slot : slots)
    if (slot.serial == serial && slot.rows_total > 0) return &slot;
  return nullptr;
}

KeyframeTextures::Slot& KeyframeTextures::claim(std::vector<Slot>& slots, std::uint64_t serial, std::uint64_t pinned_a,
                                                std::uint64_t pinned_b) {
  // A free slot, else the least recently used one that the pair on screen does not hold.
  Slot* best = nullptr;
  for (Slot& slot : slots) {
    if (slot.rows_total == 0) {
      best = &slot;
      break;
    }
    if (slot.serial == pinned_a || slot.serial == pinned_b) continue;
    if (!best || slot.last_used < best->last_used) best = &slot;
  }
  if (!best) throw Error("keyframe textures", "every texture slot holds a keyframe on screen", "report this bug");
  best->serial = serial;
  best->complete = false;
  best->rows_done = 0;
  best->harbour.reset();
  best->deep.reset();
  best->moments.clear();
  best->moments_pending = {};  // (an evicted unfinished slot's worker: waits for it to end)
  return *best;
}

void KeyframeTextures::start_harbour(Slot& slot, std::shared_ptr<const runtime::HarbourKeyframe> keyframe) {
  const int width = keyframe->surface_elevation_m.columns(), height = keyframe->surface_elevation_m.rows();
  if (!keyframe->breaking.empty() &&
      (keyframe->breaking.columns() != width || keyframe->breaking.rows() != height))
    throw Error("harbour keyframe " + std::to_string(keyframe->serial),
                "has a breaking raster of another size than its surface elevation",
                "give both rasters the harbour grid's size");
  // The slope moments' pyramid (slope_moments.hpp), sent level by level after the rows: the
  // worker's if the keyframe was staged, else computed here (a keyframe needed unstaged).
  const auto computing = std::find_if(moments_computing_.begin(), moments_computing_.end(),
                                      [&](const auto& entry) { return entry.first == keyframe->serial; });
  if (computing != moments_computing_.end()) {
    slot.moments_pending = std::move(computing->second);
    moments_computing_.erase(computing);
  } else {  // into the last sent pyramid's storage: memory already touched (not faulted in afresh)
    slope_moment_pyramid(keyframe->surface_elevation_m, spare_moments_);
    slot.moments = std::move(spare_moments_);
    spare_moments_.clear();
  }
  const auto moment_sizes = slope_moment_level_sizes(width, height);
  if (slot.width != width || slot.height != height || slot.layers != 0 || !slot.textures[0]) {
    for (int field = 0; field < kHarbourFieldCount; ++field) {
      if (!slot.textures[field]) slot.textures[field] = new_texture(GL_TEXTURE_2D);
      glBindTexture(GL_TEXTURE_2D, slot.textures[field]);
      glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, nullptr);
    }
    // Trilinear between the levels (the shader picks the level itself: textureLod), clamped.
    if (!slot.textures[kSlopeMomentsTexture]) slot.textures[kSlopeMomentsTexture] = new_texture(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, slot.textures[kSlopeMomentsTexture]);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    for (std::size_t level = 0; level < moment_sizes.size(); ++level)
      glTexImage2D(GL_TEXTURE_2D, GLint(level), GL_RGBA32F, moment_sizes[level].first, moment_sizes[level].second, 0,
                   GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, GLint(moment_sizes.size()) - 1);
    slot.width = width;
    slot.height = height;
    slot.layers = 0;
  }
  long long moment_rows = 0;
  for (const auto& size : moment_sizes) moment_rows += size.second;
  // eta rows, breaking rows, rate rows, then the moments' rows level by level
  slot.rows_total = static_cast<long long>(kHarbourFieldCount) * height + moment_rows;
  slot.harbour = std::move(keyframe);
}

void KeyframeTextures::start_deep(Slot& slot, std::shared_ptr<const runtime::DeepWaterKeyframe> keyframe) {
  const int cascades = deep_layer_count(*keyframe);
  const int n = cascades ? keyframe->cascades.front().grid_size : 0;
  for (int layer = 0; layer < cascades; ++layer) {
    const ocean::DeepWaterFrame& frame = deep_layer(*keyframe, layer);
    const std::size_t expected = std::size_t(n) * n;
    if (frame.grid_size != n || frame.surface_elevation_m.size() != expected || frame.displacement_x_m.size() != expected ||
        frame.displacement_y_m.size() != expected || frame.slope_x.size() != expected || frame.slope_y.size() != expected)
      throw Error("deep-water keyframe " + std::to_string(keyframe->serial),
                  "has cascades of different sizes or missing fields (eta, displacement, slopes)",
                  "synthesise every cascade with one grid size (DeepWaterSpecification::grid_size)");
  }
  if (cascades > 8)
    throw Error("deep-water keyframe " + std::to_string(keyframe->serial),
                "has " + std::to_string(cascades) + " cascades; the renderer draws at most 8", "use at most 8 cascades");
  if (slot.width != n || slot.height != n || slot.layers != cascades || !slot.textures[0]) {
    for (int field = 0; field < kDeepFieldCount; ++field) {
      if (!slot.textures[field]) slot.textures[field] = new_texture(GL_TEXTURE_2D_ARRAY);
      glBindTexture(GL_TEXTURE_2D_ARRAY, slot.textures[field]);
      glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R32F, n, n, cascades, 0, GL_RED, GL_FLOAT, nullptr);
    }
    slot.width = n;
    slot.height = n;
    slot.layers = cascades;
  }
  slot.rows_total = static_cast<long long>(kDeepFieldCount) * cascades * n;
  slot.deep = std::move(keyframe);
}

std::size_t KeyframeTextures::upload_rows(Slot& slot, std::size_t budget_bytes) {
  const std::size_t row_bytes = std::size_t(slot.width) * sizeof(float);
  // A calm sea (Beaufort 0) has deep-water keyframes without cascades: nothing to send, and the
  // keyframe counts as resident (else the staging loop would wait on it for ever).
  if (row_bytes == 0 || slot.rows_done >= slot.rows_total) {
    slot.rows_done = slot.rows_total;
    slot.complete = true;
    slot.moments.clear();
    slot.harbour.reset();
    slot.deep.reset();
    slot.last_used = frame_;
    return 0;
  }
  std::size_t sent = 0;
  // How many of `available` rows of `bytes_per_row` the budget left pays for (at least one in a
  // call that sent nothing yet, so a queue always advances).
  const auto affordable = [&](std::size_t bytes_per_row, long long available) {
    const std::size_t left = budget_bytes > sent ? budget_bytes - sent : 0;
    long long count = std::min<long long>(available, static_cast<long long>(std::min<std::size_t>(left / bytes_per_row, 1u << 30)));
    return count == 0 && sent == 0 ? 1LL : count;
  };
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  const long long field_rows = static_cast<long long>(kHarbourFieldCount) * slot.height;
  while (slot.rows_done < slot.rows_total) {
    if (slot.harbour && slot.rows_done >= field_rows) {
      // The slope moments' levels after the fields, in rows of RGBA32F; the worker's result,
      // waited for here if it is not ready yet (the same texels either way: the schedule of
      // bytes per frame does not depend on the threads' timing).
      if (slot.moments_pending.valid()) slot.moments = slot.moments_pending.get();
      long long row = slot.rows_done - field_rows;
      std::size_t level = 0;
      while (row >= slot.moments[level].rows) row -= slot.moments[level++].rows;
      const SlopeMomentLevel& moments = slot.moments[level];
      const std::size_t bytes_per_row = std::size_t(moments.columns) * 4 * sizeof(float);
      const long long count = affordable(bytes_per_row, moments.rows - row);
      if (count == 0) break;
      glBindTexture(GL_TEXTURE_2D, slot.textures[kSlopeMomentsTexture]);
      glTexSubImage2D(GL_TEXTURE_2D, GLint(level), 0, GLint(row), moments.columns, GLsizei(count), GL_RGBA, GL_FLOAT,
                      moments.texels.data() + std::size_t(row) * moments.columns * 4);
      slot.rows_done += count;
      sent += std::size_t(count) * bytes_per_row;
    } else if (slot.harbour) {
      const int field = static_cast<int>(slot.rows_done / slot.height), row = static_cast<int>(slot.rows_done % slot.height);
      const int count = static_cast<int>(affordable(row_bytes, slot.height - row));
      if (count == 0) break;
      glBindTexture(GL_TEXTURE_2D, slot.textures[field]);
      const Raster<float>& raster = field == 0   ? slot.harbour->surface_elevation_m
                                    : field == 1 ? slot.harbour->breaking
                                                 : slot.harbour->surface_elevation_rate_m_s;
      if (raster.size() != std::size_t(slot.width) * slot.height) {  // no breaking (nothing breaks) or no rate (linear)
        zero_row_.assign(std::size_t(slot.width), 0.f);
        for (int r = 0; r < count; ++r)
          glTexSubImage2D(GL_TEXTURE_2D, 0, 0, row + r, slot.width, 1, GL_RED, GL_FLOAT, zero_row_.data());
      } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, row, slot.width, count, GL_RED, GL_FLOAT,
                        raster.data() + std::size_t(row) * slot.width);
      }
      slot.rows_done += count;
      sent += std::size_t(count) * row_bytes;
    } else {
      const long long per_field = static_cast<long long>(slot.layers) * slot.height;
      const int field = static_cast<int>(slot.rows_done / per_field);
      const int layer = static_cast<int>((slot.rows_done / slot.height) % slot.layers);
      const int row = static_cast<int>(slot.rows_done % slot.height);
      const int count = static_cast<int>(affordable(row_bytes, slot.height - row));
      if (count == 0) break;
      glBindTexture(GL_TEXTURE_2D_ARRAY, slot.textures[field]);
      const std::vector<float>& values = deep_field(deep_layer(*slot.deep, layer), field);
      glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, row, layer, slot.width, count, 1, GL_RED, GL_FLOAT,
                      values.data() + std::size_t(row) * slot.width);
      slot.rows_done += count;
      sent += std::size_t(count) * row_bytes;
    }
  }
  if (slot.rows_done >= slot.rows_total) {
    slot.complete = true;
    if (!slot.moments.empty()) spare_moments_ = std::move(slot.moments);  // the next computed here reuses it
    slot.moments.clear();
    slot.harbour.reset();  // the GPU holds it now; the engine may let it go
    slot.deep.reset();
  }
  slot.last_used = frame_;
  return sent;
}

KeyframeTextures::Slot& KeyframeTextures::resident_harbour(const std::shared_ptr<const runtime::HarbourKeyframe>& keyframe,
                                                           std::uint64_t other, UploadCounters& counters) {
  Slot* slot = find(harbour_slots_, keyframe->serial);
  if (!slot) {
    slot = &claim(harbour_slots_, keyframe->serial, keyframe->serial, other);
    start_harbour(*slot, keyframe);
  }
  if (!slot->complete) {
    if (!slot->harbour) slot->harbour = keyframe;
    const std::size_t sent = upload_rows(*slot, kUnlimited);
    counters.bytes += sent;
    counters.forced_bytes += sent;
  }
  slot->last_used = frame_;
  std::erase_if(harbour_queue_, [&](const auto& queued) { return queued->serial == keyframe->serial; });
  return *slot;
}

KeyframeTextures::Slot& KeyframeTextures::resident_deep(const std::shared_ptr<const runtime::DeepWaterKeyframe>& keyframe,
                                                        std::uint64_t other, UploadCounters& counters) {
  Slot* slot = find(deep_slots_, keyframe->serial);
  if (!slot) {
    slot = &claim(deep_slots_, keyframe->serial, keyframe->serial, other);
    start_deep(*slot, keyframe);
  }
  if (!slot->complete) {
    if (!slot->deep) slot->deep = keyframe;
    const std::size_t sent = upload_rows(*slot, kUnlimited);
    counters.bytes += sent;
    counters.forced_bytes += sent;
  }
  slot->last_used = frame_;
  std::erase_if(deep_queue_, [&](const auto& queued) { return queued->serial == keyframe->serial; });
  return *slot;
}

KeyframeTextures::Bound KeyframeTextures::prepare(const runtime::SurfaceSnapshot& snapshot, std::size_t budget,
                                                  UploadCounters& counters) {
  ++frame_;
  Bound bound;
  // 1. The pair on screen, whole (a missing 'to' shows 'from' alone).
  const auto& harbour_from = snapshot.harbour_from ? snapshot.harbour_from : snapshot.harbour_to;
  const auto& harbour_to = snapshot.harbour_to ? snapshot.harbour_to : snapshot.harbour_from;
  pinned_harbour_[0] = harbour_from ? harbour_from->serial : 0;
  pinned_harbour_[1] = harbour_to ? harbour_to->serial : 0;
  if (harbour_from) {
    const Slot& from = resident_harbour(harbour_from, pinned_harbour_[1], counters);
    const Slot& to = resident_harbour(harbour_to, pinned_harbour_[0], counters);
    bound.harbour_eta[0] = from.textures[0];
    bound.harbour_breaking[0] = from.textures[1];
    bound.harbour_eta[1] = to.textures[0];
    bound.harbour_breaking[1] = to.textures[1];
    bound.harbour_eta_rate[0] = from.textures[2];
    bound.harbour_eta_rate[1] = to.textures[2];
    bound.harbour_slope_moments[0] = from.textures[kSlopeMomentsTexture];
    bound.harbour_slope_moments[1] = to.textures[kSlopeMomentsTexture];
  }
  const auto& deep_from = snapshot.deep_from ? snapshot.deep_from : snapshot.deep_to;
  const auto& deep_to = snapshot.deep_to ? snapshot.deep_to : snapshot.deep_from;
  pinned_deep_[0] = deep_from ? deep_from->serial : 0;
  pinned_deep_[1] = deep_to ? deep_to->serial : 0;
  if (deep_from && !deep_from->cascades.empty()) {
    if (deep_to->cascades.size() != deep_from->cascades.size() ||
        deep_to->inside_cascades.size() != deep_from->inside_cascades.size() ||
        deep_to->inside_cascade_mask != deep_from->inside_cascade_mask ||
        deep_to->cascades.front().grid_size != deep_from->cascades.front().grid_size)
      throw Error("deep-water keyframes " + std::to_string(deep_from->serial) + " and " + std::to_string(deep_to->serial),
                  "have different cascades", "blend keyframes of one deep-water field");
    const Slot& from = resident_deep(deep_from, pinned_deep_[1], counters);
    const Slot& to = resident_deep(deep_to, pinned_deep_[0], counters);
    for (int field = 0; field < kDeepFieldCount; ++field) {
      bound.deep[field][0] = from.textures[field];
      bound.deep[field][1] = to.textures[field];
    }
    bound.deep_size = from.width;
    bound.cascade_count = static_cast<int>(deep_from->cascades.size());
    bound.inside_layer_count = from.layers - bound.cascade_count;
    bound.inside_cascade_mask = deep_from->inside_cascade_mask;
    for (int layer = 0; layer < from.layers; ++layer)
      bound.tile_lengths_m.push_back(float(deep_layer(*deep_from, layer).tile_length_m));
  }
  // 2. The staged keyframes, within the budget, oldest first.
  auto advance = [&](auto& queue, std::vector<Slot>& slots, const std::uint64_t* pinned, auto start) {
    while (budget > 0 && !queue.empty()) {
      const auto keyframe = queue.front();
      Slot* slot = find(slots, keyframe->serial);
      if (!slot) {
        slot = &claim(slots, keyframe->serial, pinned[0], pinned[1]);
        (this->*start)(*slot, keyframe);
      }
      if (!slot->complete) {
        const std::size_t sent = upload_rows(*slot, budget);
        counters.bytes += sent;
        budget -= std::min(sent, budget);
      }
      if (slot->complete) queue.pop_front();
    }
  };
  advance(harbour_queue_, harbour_slots_, pinned_harbour_, &KeyframeTextures::start_harbour);
  advance(deep_queue_, deep_slots_, pinned_deep_, &KeyframeTextures::start_deep);
  return bound;
}

}  // namespace nearshore::playback
