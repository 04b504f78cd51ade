// Timing for erkn_integrate_benchmark: groups of contenders (a cell: erkn and its peer) timed in
// interleaved rounds, thread CPU time, each sample `reps` whole runs (setup included), and the
// ratio of two contenders as the median over rounds of their per-round ratio (a load change on
// the shared machine then hits both sides of a ratio alike).
//
// Every round visits every group in turn (a Schedule), so one group's samples are spread over the
// whole run rather than taken in one ~0.15 s stretch, which a slow spell of this shared machine
// could cover whole (stellar orbits Strang, compiled: erkn 0.75 of the peer in one run, 1.34 in
// the next, every round alike; N = 8192 and 256^2 cells moved 5-20 %). The caller pins the thread
// to one CPU (the two vCPUs differ in speed from moment to moment), for every contender alike.
// The caller also turns off glibc malloc's fastbins (mallopt(M_MXFAST, 0)), for every contender
// alike (steady_malloc). With them, microsecond runs (Duffing, stellar orbits; erkn's and the
// peer's alike) had 24-30 samples of ~8500 per run over 2x (most 3-11x) their contender's median,
// at (round, contender) positions that moved from process to process. perf (cpu-clock, each slow
// sample's window against a normal sample of the same contender): 55-75 % of the slow ones in
// malloc_consolidate, 15-30 % in unlink_chunk, ~0 in the normal ones; no page faults, no system
// time (getrusage). gdb: the consolidations come from requests glibc's per-thread cache does not
// serve (the peer's fftw_malloc, a memalign; erkn's FlowCoefficients array) while freed small
// blocks wait in fastbins, so how often a run pays one depends on the heap the other ~150 groups
// leave: a run repeated alone in a process had none of this (12 processes of --scene Duffing /
// stellar: no sample over 2x), and its medians moved too (stellar ABA1064, erkn / peer with
// compensation off: 0.68 alone, 0.76-0.97 in six full runs, 0.68 without fastbins). Without
// fastbins a freed block is coalesced at once: the full run had 2 samples over 2x (2.1x, 2.7x).
// Without them alone, though, the 256^2 grid's erkn Strang, compiled, defaults, took 1.47-1.51x
// the peer in two full runs (1.01-1.05 in runs of that scene alone): its 0.5 MB buffers, above
// glibc's mmap threshold or freed into a heap top over the trim threshold, came back as fresh
// pages. So the heap is also kept (M_TRIM_THRESHOLD 1 GiB) and such buffers taken from it
// (M_MMAP_THRESHOLD 32 MiB, glibc's maximum), as glibc's dynamic thresholds do in a warm
// process: that cell 1.01 in a full run, every other ratio within 9 % of the run without.
//
// A sample's reps come from batches of runs (sample_reps), not from one timed run: a single run
// of a microsecond contender sometimes took many times its cost (a stellar-orbit group's ~20 us
// run timed at ~0.4 ms), so that group's samples were 0.2 ms of 10 runs rather than 4 ms, and its
// ratio moved 25 % between two full runs (P3 SRKN11b, compensation off: 0.74, then 0.93; 3 of
// 199 groups had samples under 2 ms in that run, none in the one before); in runs of the
// stellar-orbit scene alone the implicit group's reps ranged 83-662 from process to process.
//
// Every run of a sample starts with the stack at another offset within a 4 KiB page (the next
// of a low-discrepancy sequence, the same ones for every contender of a round; at_stack_offset),
// so that a sample averages over offsets rather than taking the one that address-space
// randomisation gave the process. The offset moves the explicit ratios by more than their
// margins: sine-Gordon N = 32 Strang, erkn compiled / the peer, compensation off, with the
// process's stack fixed (setarch -R) and every run of the benchmark at one offset, 0 / 352 / 960 /
// 1920 / 2528 / 2880 / 3488 bytes: 1.001 / 0.990 / 1.025 / 1.021 / 1.012 / 0.994 / 1.026 (two
// runs each, the other CPU busy); the same binary in six successive processes on a quiet
// machine (randomised) 1.002-1.027, with these offsets 0.995-1.006. (perf annotate: libm's sin, ~65
// % of that run, spends ~60 % of its time on reloading the control word it has just stored to its
// stack frame.)
#pragma once

#include <alloca.h>
#include <malloc.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "host_state.hpp"
#include "thread_seconds.hpp"

namespace bench {

struct TimingPlan {
  int rounds = 7;            // interleaved rounds
  double min_sample = 5e-3;  // seconds of CPU per sample (reps runs of the first contender)
};

/// Pins the calling thread to the lowest CPU it may run on (Linux); false where it cannot.
inline bool pin_to_one_cpu() {
  cpu_set_t allowed;
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return false;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &allowed)) {
      cpu_set_t one;
      CPU_ZERO(&one);
      CPU_SET(c, &one);
      return sched_setaffinity(0, sizeof one, &one) == 0;
    }
  return false;
}

/// glibc malloc in a steady state for every contender (see the header): no fastbins (freed small
/// blocks coalesced at once rather than by malloc_consolidate on a later request), the heap never
/// trimmed, blocks up to 32 MiB taken from it rather than mapped; false where it cannot.
inline bool steady_malloc() {
#if defined(M_MXFAST) && defined(M_TRIM_THRESHOLD) && defined(M_MMAP_THRESHOLD)
  return mallopt(M_MXFAST, 0) == 1 && mallopt(M_TRIM_THRESHOLD, 1 << 30) == 1 &&
         mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1;
#else
  return false;
#endif
}

/// Calls f with the stack `bytes` deeper than this call's frame (f's frame and its callees').
[[gnu::noinline]] inline void at_stack_offset(size_t bytes, const std::function<void()>& f) {
  char* pad = static_cast<char*>(alloca(bytes + 1));
  asm volatile("" : : "r"(pad) : "memory");  // (the allocation kept)
  f();
}
/// The k-th stack offset: k times the golden section of a 4 KiB page, modulo the page (multiples
/// of 32 bytes, 128 of them), so that any number of consecutive ones spreads over the page.
inline size_t stack_offset(size_t k) { return k * 2528 % 4096; }

/// CPU seconds of n runs of `run`.
inline double batch_seconds(const std::function<void()>& run, long n) {
  const double start = thread_seconds();
  for (long j = 0; j < n; ++j) run();
  return thread_seconds() - start;
}

/// Runs per sample so that a sample of `run` takes at least min_sample: the run's cost from the
/// faster of two batches of at least min_sample / 4 each (batch sizes doubled until then), so
/// one slow run (an interrupt, a first touch) does not shorten every sample of the group. The
/// second batch starts at the first's size and grows too: after a slow run in the first batch
/// that size is small (a single 20 us run as the second batch misjudged the test's contender
/// 1 time in 20 under load).
inline int sample_reps(const std::function<void()>& run, double min_sample) {
  const auto per_run = [&](long& n) {  // seconds per run of one batch, n doubled as needed
    double t = batch_seconds(run, n);
    while (t < min_sample / 4) t = batch_seconds(run, n *= 2);
    return t / double(n);
  };
  long n = 1;
  const double first = per_run(n);
  const double once = std::max(std::min(first, per_run(n)), 1e-9);
  return std::max(1, int(std::ceil(min_sample / once)));
}

/// A group's rounds in the host's states (host_state.hpp): per round the probe's reading before
/// its sample (the neighbour median) and whether the run's split calls it slow;
/// empty when the schedule ran without a probe.
struct RoundStates {
  std::vector<double> probe;
  std::vector<bool> slow;
  size_t slow_rounds() const { return size_t(std::count(slow.begin(), slow.end(), true)); }
};

/// The medians of x[r] over a group's fast rounds and over its slow rounds (NaN where none).
inline std::pair<double, double> median_by_state(const std::vector<double>& x,
                                                 const RoundStates& s) {
  std::vector<double> fast, slow;
  for (size_t r = 0; r < s.slow.size(); ++r) (s.slow[r] ? slow : fast).push_back(x[r]);
  return {median(fast), median(slow)};
}

/// Readings of the probe taken within this many places of each other in time are smoothed
/// together (neighbour_median): 2 * 2 + 1 = 5 readings span 0.1-1 s of a run, states last 3 s
/// and more.
inline constexpr size_t kProbeNeighbours = 2;

/// Groups of contenders timed together: add() every group, then run(). seconds[c][r] of a group
/// is its contender c's CPU seconds per run in round r; round r samples every group in the order
/// added, a group's contenders in the order rotated by r.
class Schedule {
 public:
  using Contenders = std::vector<std::function<void()>>;
  using Seconds = std::vector<std::vector<double>>;
  using Done = std::function<void(const Seconds&, const RoundStates&)>;
  /// `done` receives the group's seconds and states once every round has run.
  void add(Contenders contenders, Done done) {
    groups_.push_back({std::move(contenders), std::move(done), 0, {}, {}});
  }
  /// Every contender runs once untimed first (warm-up: FFTW plans, caches), then `reps` runs per
  /// sample, reps chosen per group so that its contender 0's sample takes at least
  /// plan.min_sample (sample_reps). With a probe (returning a reading of the host's state, e.g.
  /// integrate_cells.hpp's ExplicitPathProbe::read), it is read before every group's sample and
  /// the run's states split from the readings (returned; one state without a probe).
  StateSplit run(const TimingPlan& plan, const std::function<double()>& probe = {}) {
    for (Group& g : groups_) g.reps = warm_up(g.contenders, plan);
    for (Group& g : groups_)
      g.seconds.assign(g.contenders.size(), std::vector<double>(size_t(plan.rounds)));
    std::vector<double> readings;  // in time order: round-major
    for (int r = 0; r < plan.rounds; ++r)
      for (Group& g : groups_) {
        if (probe) readings.push_back(probe());
        sample(g, size_t(r));
      }
    const StateSplit split = label(readings);
    for (Group& g : groups_) g.done(g.seconds, g.states);
    groups_.clear();
    return split;
  }

 private:
  struct Group {
    Contenders contenders;
    Done done;
    int reps;
    Seconds seconds;
    RoundStates states;
  };
  /// Each group's RoundStates from the readings (round-major), smoothed over neighbours in time.
  StateSplit label(const std::vector<double>& readings) {
    if (readings.empty()) return {};
    const std::vector<double> smooth = neighbour_median(readings, kProbeNeighbours);
    const StateSplit split = split_states(smooth);
    for (size_t i = 0; i < smooth.size(); ++i) {
      RoundStates& s = groups_[i % groups_.size()].states;
      s.probe.push_back(smooth[i]);
      s.slow.push_back(split.is_slow(smooth[i]));
    }
    return split;
  }
  static int warm_up(const Contenders& contenders, const TimingPlan& plan) {
    for (const auto& run : contenders) run();
    return sample_reps(contenders[0], plan.min_sample);
  }
  static void sample(Group& g, size_t r) {
    const size_t k = g.contenders.size();
    for (size_t i = 0; i < k; ++i) {
      const size_t c = (i + r) % k;
      const size_t first = r * size_t(g.reps);  // (this round's offsets: the next reps)
      const double start = thread_seconds();
      for (size_t j = 0; j < size_t(g.reps); ++j)
        at_stack_offset(stack_offset(first + j), g.contenders[c]);
      g.seconds[c][r] = (thread_seconds() - start) / g.reps;
    }
  }
  std::vector<Group> groups_;
};

/// One group's seconds[c][r] (Schedule).
inline std::vector<std::vector<double>> time_rounds(
    const std::vector<std::function<void()>>& contenders, const TimingPlan& plan) {
  std::vector<std::vector<double>> seconds;
  Schedule schedule;
  schedule.add(contenders, [&](const Schedule::Seconds& s, const RoundStates&) { seconds = s; });
  schedule.run(plan);
  return seconds;
}

/// Per round, a[r] / b[r].
inline std::vector<double> ratios(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> r;
  for (size_t i = 0; i < a.size(); ++i) r.push_back(a[i] / b[i]);
  return r;
}

/// The contenders [from, to) of a group.
inline std::vector<size_t> contender_range(size_t from, size_t to) {
  std::vector<size_t> c;
  for (size_t i = from; i < to; ++i) c.push_back(i);
  return c;
}

/// Per round, the median over the given contenders of seconds per grad U (seconds t[c][r],
/// gradient evaluations ev[c] per run).
inline std::vector<double> per_grad_median(const std::vector<std::vector<double>>& t,
                                           const std::vector<double>& ev,
                                           const std::vector<size_t>& contenders) {
  std::vector<double> out(t[0].size());
  for (size_t r = 0; r < out.size(); ++r) {
    std::vector<double> x;
    for (size_t c : contenders) x.push_back(t[c][r] / ev[c]);
    out[r] = median(x);
  }
  return out;
}

/// The median over rounds of a[r] / b[r].
inline double median_ratio(const std::vector<double>& a, const std::vector<double>& b) {
  return median(ratios(a, b));
}

}  // namespace bench
