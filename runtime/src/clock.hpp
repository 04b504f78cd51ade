// The clocks of Statistics::wall_time / cpu_time and of the accuracy pilot (accuracy.cpp).
#pragma once

#include <chrono>
#include <ctime>

namespace erkn::detail {

inline double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// CPU time of the calling thread: an Ensemble's trajectories on other threads do not count.
inline double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

}  // namespace erkn::detail
