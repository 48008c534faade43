#pragma once
// GPU time per pass of the water renderer (private to it; FrameStatistics::gpu). Needs the
// renderer's current GL context.
#include <glad/gl.h>

#include "nearshore/playback/water_renderer.hpp"

namespace nearshore::playback {

// GPU time per pass (GL_TIME_ELAPSED, core since OpenGL 3.3): one query object per pass in each of
// kFrames sets used in turn, read kFrames - 1 frames later at the latest and only once the driver
// says the result is there (GL_QUERY_RESULT_AVAILABLE), so the frame loop never waits for the GPU.
// A set still pending when its turn comes again (the GPU more than kFrames - 1 frames behind) leaves
// that frame untimed rather than wait. Timer queries cannot nest: the passes are timed one after the
// other, and a frame is left untimed when the host has its own GL_TIME_ELAPSED query running.
class PassTimer {
 public:
  static constexpr int kFrames = 4;
  void release() {  // with the context current (WaterRenderer's destructor)
    if (queries_[0][0]) glDeleteQueries(kFrames * kGpuPassCount, &queries_[0][0]);
    *this = PassTimer{};
  }
  // Starts a frame: collects what the earlier frames' queries have finished (newest wins) into
  // `times`, then opens this frame's set when it is free.
  void begin_frame(bool enabled, GpuPassTimes& times) {
    end_pass();  // a frame that threw between begin_pass and end_pass
    ++frame_;
    times = latest_;
    times.frames_behind = latest_.measured ? int(frame_ - latest_frame_) : 0;
    timing_ = false;
    if (!enabled || !available()) return;
    poll(times);
    GLint running = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_CURRENT_QUERY, &running);
    Set& set = sets_[frame_ % kFrames];
    if (running || set.pending) return;
    set = Set{};
    set.frame = frame_;
    timing_ = true;
  }
  void begin_pass(GpuPass pass) {
    if (!timing_) return;
    end_pass();
    Set& set = sets_[frame_ % kFrames];
    glBeginQuery(GL_TIME_ELAPSED, queries_[frame_ % kFrames][int(pass)]);
    set.used[int(pass)] = true;
    set.pending = true;
    active_ = true;
  }
  void end_pass() {
    if (!active_) return;
    glEndQuery(GL_TIME_ELAPSED);
    active_ = false;
  }

 private:
  struct Set {
    bool pending = false;
    bool used[kGpuPassCount] = {};
    unsigned long long frame = 0;
  };
  // Whether the driver counts time at all (GL_QUERY_COUNTER_BITS 0: no timer; asked once).
  bool available() {
    if (checked_) return queries_[0][0] != 0;
    checked_ = true;
    GLint bits = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    if (glGetError() != GL_NO_ERROR || bits <= 0) return false;
    glGenQueries(kFrames * kGpuPassCount, &queries_[0][0]);
    return true;
  }
  // Reads every pending set whose last-issued query has its result (the GPU finishes queries in
  // order), oldest first, so `latest_` ends on the newest finished frame.
  void poll(GpuPassTimes& times) {
    for (int age = kFrames; age >= 1; --age) {  // age kFrames: the set this frame would reuse
      const int slot = int((frame_ + kFrames - unsigned(age)) % kFrames);
      Set& set = sets_[slot];
      if (!set.pending) continue;
      GLuint available_all = 1;
      for (int pass = 0; pass < kGpuPassCount && available_all; ++pass)
        if (set.used[pass])
          glGetQueryObjectuiv(queries_[slot][pass], GL_QUERY_RESULT_AVAILABLE, &available_all);
      if (!available_all) break;  // a later set cannot be done before this one
      GpuPassTimes read;
      read.measured = true;
      for (int pass = 0; pass < kGpuPassCount; ++pass) {
        if (!set.used[pass]) continue;
        GLuint64 elapsed_ns = 0;
        glGetQueryObjectui64v(queries_[slot][pass], GL_QUERY_RESULT, &elapsed_ns);
        read.ms[std::size_t(pass)] = 1e-6 * double(elapsed_ns);
        read.total_ms += read.ms[std::size_t(pass)];
      }
      set.pending = false;
      latest_ = read;
      latest_frame_ = set.frame;
    }
    times = latest_;
    times.frames_behind = latest_.measured ? int(frame_ - latest_frame_) : 0;
  }

  GLuint queries_[kFrames][kGpuPassCount] = {};
  Set sets_[kFrames];
  GpuPassTimes latest_;
  unsigned long long frame_ = 0, latest_frame_ = 0;
  bool checked_ = false, timing_ = false, active_ = false;
};

}  // namespace nearshore::playback
