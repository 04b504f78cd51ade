// The benchmarks' clock: CPU time of the calling thread (the machine is shared, so wall time
// would count other programs).
#pragma once

#include <ctime>

namespace bench {

inline double thread_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

}  // namespace bench
