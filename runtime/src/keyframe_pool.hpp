#pragma once
// Recycling of published keyframes: a keyframe is published as std::shared_ptr<const T> whose
// deleter hands the object back here when the last holder (a ring, a snapshot) lets it go, so the
// worker decodes the next step into memory that is already the right size. The hand-back takes a
// mutex, which orders every reader's last use before the worker's next write (no data race).
// If the pool is gone (the engine destroyed while a host still holds a snapshot) the object is
// simply deleted.
#include <memory>
#include <mutex>
#include <vector>

namespace nearshore::runtime {

template <class T>
class KeyframePool {
 public:
  KeyframePool() : state_(std::make_shared<State>()) {}
  ~KeyframePool() {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    state_->closed = true;
    state_->allocated -= static_cast<long long>(state_->free.size());
    state_->free.clear();
  }
  KeyframePool(const KeyframePool&) = delete;
  KeyframePool& operator=(const KeyframePool&) = delete;

  /// A recycled object (its buffers keep their size) or a new one.
  std::unique_ptr<T> acquire() {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    if (!state_->free.empty()) {
      std::unique_ptr<T> object = std::move(state_->free.back());
      state_->free.pop_back();
      return object;
    }
    ++state_->allocated;
    return std::make_unique<T>();
  }
  /// Hands an object back without publishing it (a result that is no longer wanted).
  void recycle(std::unique_ptr<T> object) { give_back(state_, object.release()); }
  /// Makes `object` immutable and shareable; it comes back here when its last holder lets go.
  std::shared_ptr<const T> publish(std::unique_ptr<T> object) {
    std::shared_ptr<State> state = state_;
    return std::shared_ptr<const T>(object.release(), [state](const T* p) { give_back(state, const_cast<T*>(p)); });
  }
  /// Objects alive: in use anywhere, or waiting here.
  long long allocated() const {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    return state_->allocated;
  }

 private:
  struct State {
    std::mutex mutex;
    std::vector<std::unique_ptr<T>> free;
    bool closed = false;
    long long allocated = 0;
  };
  static void give_back(const std::shared_ptr<State>& state, T* object) {
    if (!object) return;
    const std::lock_guard<std::mutex> lock(state->mutex);
    if (state->closed) {
      --state->allocated;
      delete object;
      return;
    }
    state->free.emplace_back(object);
  }
  std::shared_ptr<State> state_;
};

}  // namespace nearshore::runtime
