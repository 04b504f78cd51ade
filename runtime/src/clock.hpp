// The clocks of Statistics::wall_time / cpu_time and of the accuracy pilot (accuracy.cpp).
#pragma once

#include <chrono>
#include <ctime>

namespace erkn::detail {

/// The reading of the POSIX clock `clock` in seconds.
inline double posix_seconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// (Linux: CLOCK_MONOTONIC, which steady_clock reads too, so that coarse_wall_seconds compares
// with it.)
inline double wall_seconds() {
#ifdef CLOCK_MONOTONIC_COARSE
  return posix_seconds(CLOCK_MONOTONIC);
#else
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
#endif
}

/// wall_seconds() as of the clock's last tick (Linux: CLOCK_MONOTONIC_COARSE; it lags by up to a
/// tick, 1-4 ms, and never leads): 9 ns a read on the benchmark machine against 62-66 ns for
/// wall_seconds(). Elsewhere wall_seconds() itself.
inline double coarse_wall_seconds() {
#ifdef CLOCK_MONOTONIC_COARSE
  return posix_seconds(CLOCK_MONOTONIC_COARSE);
#else
  return wall_seconds();
#endif
}

/// CPU time of the calling thread: an Ensemble's trajectories on other threads do not count.
inline double cpu_seconds() { return posix_seconds(CLOCK_THREAD_CPUTIME_ID); }

}  // namespace erkn::detail
