// The host's fast and slow states (issue 17): each virtual CPU of this host switches between a
// fast and a slow state lasting ~3 s to over 80 s, following the CPU, not the process; the slow
// state costs latency- and memory-bound code most (erkn's implicit stage 1.2-1.5x, the explicit
// path 1.1-1.3x). erkn_integrate_benchmark reads a probe before every sample (a group's visit in
// a round), on the CPU the run is pinned to, and labels each sample fast or slow from the run's
// readings, so a reader sees which state a number comes from.
//
// The probe (integrate_cells.hpp: ExplicitPathProbe) is the explicit path's CPU per grad U: every
// explicit registry method with plain kicks run once on Duffing (P2, construct + 200 steps), the
// median over them; ~0.3 ms. Measured against candidates, each timed for 0.3 ms in turn, pinned,
// over 3-7 minutes in three runs with state changes: erkn's Strang on P2 read 1.28-1.36x slower
// in the slow state (misclassified 2-9 % after the 5-reading median used here), erkn's implicit
// runs 1.38-1.48x, ABA1064 on P3 1.12-1.20x; dependent-load walks through 16-128 KB arrays 1.02x
// to 1.76x depending on the run and on how they were called (a 32 KB walk read 1.38x in two
// runs, yet the same walk read 1.5 ns flat in the benchmark's process while its twin in the
// experiment read 3.3-4 ns: not understood, so not used); a store-to-load chain 0.99-1.06x.
// The explicit path is what the cells' ratios divide by, so its state is theirs.
//
// The labels: the readings (each replaced by the median of itself and its 4 neighbours in
// time) split in two where the between-class variance of their logarithms is largest (Otsu); two
// states only if both hold several readings and their medians differ by kMinStateGap or more.
// Within a state the smoothed readings vary 0.6-0.8 % (MAD, three stretches of 400-700 readings
// in --short runs): a unimodal series of such noise splits into medians ~2 % apart, one state.
// The host's readings are not two clean levels: --short runs with other work on the machine
// read 14.7 and 16.0 (8.7 % apart), 14.8 and 15.5-16.4, and 14.7, 16.3 and 17.6 ns per grad U in
// stretches of 5-30 s; the implicit cells that moved 25-30 % between two runs had 5 of 7 rounds
// above 16.0 in one and 1 of 7 in the other. So a slower stretch counts as a state from 5 % up.
// A test of bimodality proper (the split's gap against its groups' spreads) was tried: it called
// the first of those runs one state (gap 1.8 spreads, a unimodal normal or uniform series gives
// 1.6-2.0), so it is not used; a flat spread of readings over 10 % and more is split too, and its
// labels then say which rounds ran 5 % or more slower. Otherwise one state throughout, which a
// single run cannot name.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace bench {

inline double median(std::vector<double> x) {
  if (x.empty()) return NAN;
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

/// Each x[i] replaced by the median of x[i - half .. i + half] (fewer at the ends).
inline std::vector<double> neighbour_median(const std::vector<double>& x, size_t half) {
  std::vector<double> out(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const size_t lo = i >= half ? i - half : 0, hi = std::min(x.size(), i + half + 1);
    out[i] = median(std::vector<double>(x.begin() + long(lo), x.begin() + long(hi)));
  }
  return out;
}

/// Two states of a series of probe readings, or one.
struct StateSplit {
  bool two_states = false;
  double threshold = NAN;         // readings above it are slow (two states only)
  double fast = NAN, slow = NAN;  // median reading of each state (one state: both the median)
  bool is_slow(double reading) const { return two_states && reading > threshold; }
};

inline constexpr double kMinStateGap = 1.05;
inline constexpr size_t kMinStateReadings = 5;

/// The split of log readings s (sorted) with the largest between-class variance: the number of
/// readings below it, each side at least kMinStateReadings (0 if s is too short).
inline size_t otsu_split(const std::vector<double>& s) {
  const size_t n = s.size();
  const double total = std::accumulate(s.begin(), s.end(), 0.0);
  double below = 0, best = -1;
  size_t at = 0;
  for (size_t k = 1; k < n; ++k) {
    below += s[k - 1];
    if (k < kMinStateReadings || n - k < kMinStateReadings) continue;
    const double d = below / double(k) - (total - below) / double(n - k);
    const double between = double(k) * double(n - k) * d * d;
    if (between > best) best = between, at = k;
  }
  return at;
}

/// The run's states from its (smoothed) probe readings: see the header.
inline StateSplit split_states(const std::vector<double>& readings) {
  StateSplit out;
  out.fast = out.slow = median(readings);
  std::vector<double> s;
  for (double r : readings) s.push_back(std::log(r));
  std::sort(s.begin(), s.end());
  const size_t k = otsu_split(s);
  if (k == 0) return out;
  const std::vector<double> lo(s.begin(), s.begin() + long(k)), hi(s.begin() + long(k), s.end());
  if (median(hi) - median(lo) < std::log(kMinStateGap)) return out;
  out.two_states = true;
  out.threshold = std::exp(0.5 * (s[k - 1] + s[k]));
  out.fast = std::exp(median(lo)), out.slow = std::exp(median(hi));
  return out;
}

}  // namespace bench
