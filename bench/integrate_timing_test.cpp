// bench/integrate_timing.hpp's sample_reps: a sample's runs sized from the contender's cost, not
// from one slow run; and with a contender slow on every run, sized from that (negative control).
#include "integrate_timing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace {

/// Spins for `seconds` of the thread's CPU time.
void spin(double seconds) {
  const double start = bench::thread_seconds();
  while (bench::thread_seconds() - start < seconds) {
  }
}

constexpr double kRun = 20e-6, kSlow = 2e-3, kSample = 4e-3;  // a run, a slow run, a sample

/// A contender of kRun per run whose call number `slow_call` (from 1) takes kSlow.
std::function<void()> once_slow(int slow_call) {
  return [calls = 0, slow_call]() mutable { spin(++calls == slow_call ? kSlow : kRun); };
}

TEST(SampleReps, OneSlowRunDoesNotShortenTheSamples) {
  const int ideal = int(kSample / kRun);
  for (int slow_call : {1, 2, 3, 5, 8}) {
    const int reps = bench::sample_reps(once_slow(slow_call), kSample);
    EXPECT_GE(reps, ideal / 2) << "slow call " << slow_call;
    EXPECT_LE(reps, ideal + 1) << "slow call " << slow_call;  // spin overshoots, never undershoots
  }
}

TEST(SampleReps, TheSlowRunIsThereAndOneTimedRunWouldHaveMetIt) {
  // What the single timed run (the calibration before sample_reps) saw of the contender above.
  auto run = once_slow(1);
  const double start = bench::thread_seconds();
  run();
  EXPECT_GE(bench::thread_seconds() - start, kSlow);
  EXPECT_LE(int(std::ceil(kSample / kSlow)), 2);
}

TEST(SampleReps, ContenderSlowOnEveryRunGetsFewReps) {
  EXPECT_EQ(bench::sample_reps([] { spin(kSlow); }, kSample), 2);
  EXPECT_EQ(bench::sample_reps([] { spin(2 * kSample); }, kSample), 1);
}

}  // namespace

TEST(PerGradMedian, TakesTheListedContendersOnlyPerRound) {
  // Seconds t[c][r] of four contenders over two rounds; gradient evaluations per run ev[c].
  const std::vector<std::vector<double>> t = {{2, 4}, {100, 100}, {9, 3}, {8, 16}};
  const std::vector<double> ev = {2, 1, 3, 4};  // per grad: {1, 2}, {100, 100}, {3, 1}, {2, 4}
  EXPECT_EQ(bench::per_grad_median(t, ev, {0, 2, 3}), (std::vector<double>{2, 2}));
  // Negative control: with the outlier contender 1 listed the median moves.
  EXPECT_EQ(bench::per_grad_median(t, ev, bench::contender_range(0, 4)),
            (std::vector<double>{2.5, 3}));
}

namespace {
/// The address of a local of a function called by at_stack_offset(bytes, ...)'s callee.
[[gnu::noinline]] std::uintptr_t frame_address() {
  volatile char local = 0;
  return reinterpret_cast<std::uintptr_t>(&local);
}
std::uintptr_t callee_frame(size_t bytes) {
  std::uintptr_t at = 0;
  bench::at_stack_offset(bytes, [&] { at = frame_address(); });
  return at;
}
/// The largest gap between 7 consecutive offsets from `first` on the page, wrapping round.
size_t largest_gap(size_t (*offset)(size_t), size_t first) {
  std::vector<size_t> at;
  for (size_t k = first; k < first + 7; ++k) at.push_back(offset(k));
  std::sort(at.begin(), at.end());
  at.push_back(at.front() + 4096);
  size_t gap = 0;
  for (size_t i = 0; i + 1 < at.size(); ++i) gap = std::max(gap, at[i + 1] - at[i]);
  return gap;
}
}  // namespace

TEST(StackOffset, TheCalleeRunsThatMuchDeeper) {
  const std::uintptr_t base = callee_frame(0);
  for (size_t bytes : {32, 352, 2528, 4064}) {
    const std::intptr_t deeper = std::intptr_t(base - callee_frame(bytes));
    EXPECT_GE(deeper, std::intptr_t(bytes)) << bytes;  // (alloca rounds up to the alignment)
    EXPECT_LE(deeper, std::intptr_t(bytes) + 32) << bytes;
  }
  EXPECT_EQ(callee_frame(0), base);  // negative control: no offset, the same frame
}

TEST(StackOffset, ConsecutiveOffsetsSpreadOverThePage) {
  // A round of 7 runs leaves no quarter of the page without an offset, wherever it starts.
  for (size_t first : {0, 5, 100, 127}) {
    EXPECT_LT(largest_gap(bench::stack_offset, first), 1024u) << first;
    EXPECT_EQ(bench::stack_offset(first) % 32, 0u) << first;
  }
  // Negative control: offsets 32 bytes apart leave most of the page out.
  EXPECT_GT(largest_gap([](size_t k) { return k * 32 % 4096; }, 0), 3000u);
}
