#pragma once
// FFTW's planner and plan destruction are not thread-safe (only fftwf_execute* is, FFTW manual
// section 5.4): every plan the ocean library makes or destroys holds this lock (deep_water.cpp).
#include <mutex>

namespace nearshore::ocean::detail {

std::mutex& fftw_planner_mutex();

}  // namespace nearshore::ocean::detail
