// bench/host_state.hpp: the host's two states told apart in a bimodal series of probe readings,
// one state in unimodal ones (negative controls: normal, uniform over 6 %, heavy-tailed, two
// levels too close); the labels through the Schedule; the probe's reading;
// and the run-to-run comparison's states of two runs from their csv files (integrate_markdown.hpp).
#include "host_state.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>

#include "integrate_markdown.hpp"

namespace {

using bench::split_states;

constexpr double kFast = 14.8, kSlowFactor = 1.15;  // the host's states, ns per grad U (measured)

/// n readings: states in blocks of `block` readings (every other block slow when `slow_blocks`),
/// lognormal noise of relative size `noise`; `slow` receives the true labels.
std::vector<double> blocks(size_t n, size_t block, double slow_factor, double noise,
                           std::vector<bool>* slow = nullptr, unsigned seed = 1) {
  std::mt19937 g(seed);
  std::normal_distribution<double> e(0, noise);
  std::vector<double> x;
  for (size_t i = 0; i < n; ++i) {
    const bool s = (i / block) % 2 == 1;
    if (slow) slow->push_back(s);
    x.push_back(kFast * (s ? slow_factor : 1.0) * std::exp(e(g)));
  }
  return x;
}

TEST(HostState, TwoStatesFoundAndLabelled) {
  for (double slow_factor : {1.087, kSlowFactor, 1.2})  // (1.087: the closest levels measured)
    for (double noise : {0.005, 0.01, 0.02}) {  // (within a state: 0.6-0.8 % after smoothing)
      std::vector<bool> truth;
      const auto x = bench::neighbour_median(blocks(1400, 150, slow_factor, noise, &truth), 2);
      const bench::StateSplit s = split_states(x);
      ASSERT_TRUE(s.two_states) << slow_factor << " noise " << noise;
      EXPECT_NEAR(s.fast, kFast, 0.02 * kFast);
      EXPECT_NEAR(s.slow, kFast * slow_factor, 0.02 * kFast * slow_factor);
      size_t wrong = 0;
      for (size_t i = 0; i < x.size(); ++i) wrong += s.is_slow(x[i]) != truth[i];
      EXPECT_LE(wrong, x.size() / 50) << slow_factor << " noise " << noise;
    }
}

TEST(HostState, ShortSlowSpellFound) {  // 10 readings of 700 slow (one state lasting ~3 s)
  std::vector<double> x = blocks(700, 700, kSlowFactor, 0.01);
  for (size_t i = 300; i < 310; ++i) x[i] *= kSlowFactor;
  const bench::StateSplit s = split_states(bench::neighbour_median(x, 2));
  ASSERT_TRUE(s.two_states);
  EXPECT_TRUE(s.is_slow(x[305]));
  EXPECT_FALSE(s.is_slow(x[100]));
}

TEST(HostState, UnimodalSeriesAreOneState) {  // negative controls, noise 2-3x the probe's
  std::mt19937 g(3);
  std::normal_distribution<double> normal(0, 0.025);
  std::uniform_real_distribution<double> uniform(0, 0.06);
  std::student_t_distribution<double> t3(3);
  std::vector<double> n, u, t;
  for (int i = 0; i < 1400; ++i)
    n.push_back(kFast * std::exp(normal(g))), u.push_back(kFast * std::exp(uniform(g))),
        t.push_back(kFast * std::exp(0.02 * t3(g)));
  for (const auto* x : {&n, &u, &t}) {
    const bench::StateSplit s = split_states(*x);
    EXPECT_FALSE(s.two_states);
    EXPECT_FALSE(s.is_slow(*std::max_element(x->begin(), x->end())));
    EXPECT_NEAR(s.fast, bench::median(*x), 1e-12);
  }
}

TEST(HostState, IsolatedOutliersAreNotAState) {  // an interrupt spoils one reading, not a state
  std::vector<double> x = blocks(1400, 1400, kSlowFactor, 0.03);
  for (size_t i = 7; i < x.size(); i += 97) x[i] *= 2.5;
  EXPECT_FALSE(split_states(bench::neighbour_median(x, 2)).two_states);
}

TEST(HostState, LevelsCloserThanTheGapAreOneState) {  // two clean levels 3 % apart
  EXPECT_FALSE(split_states(blocks(1400, 150, 1.03, 0.002)).two_states);
  EXPECT_TRUE(split_states(blocks(1400, 150, 1.07, 0.002)).two_states);  // (the gap itself)
}

TEST(HostState, TooFewReadingsAreOneState) {
  EXPECT_FALSE(split_states({1, 1, 2, 2}).two_states);
  EXPECT_FALSE(split_states({}).two_states);
}

TEST(HostState, ScheduleLabelsEachGroupsRounds) {
  // Scripted readings, round-major over 3 groups x 6 rounds: rounds 3-5 slow.
  std::vector<double> script;
  for (int r = 0; r < 6; ++r)
    for (int g = 0; g < 3; ++g) script.push_back(r < 3 ? 3.0 : 4.5);
  size_t next = 0;
  bench::Schedule schedule;
  std::vector<bench::RoundStates> states(3);
  for (size_t g = 0; g < 3; ++g)
    schedule.add({[] {}}, [&states, g](const bench::Schedule::Seconds&,
                                       const bench::RoundStates& s) { states[g] = s; });
  const bench::StateSplit split = schedule.run({6, 1e-5}, [&] { return script.at(next++); });
  EXPECT_EQ(next, script.size());
  ASSERT_TRUE(split.two_states);
  for (const bench::RoundStates& s : states) {
    EXPECT_EQ(s.slow, (std::vector<bool>{false, false, false, true, true, true}));
    EXPECT_EQ(s.slow_rounds(), 3u);
    EXPECT_EQ(bench::median_by_state({1, 2, 3, 10, 20, 30}, s), std::make_pair(2.0, 20.0));
  }
}

TEST(HostState, ScheduleWithoutProbeHasNoStates) {
  bench::Schedule schedule;
  bench::RoundStates states{{1.0}, {true}};
  schedule.add({[] {}},
               [&](const bench::Schedule::Seconds&, const bench::RoundStates& s) { states = s; });
  EXPECT_FALSE(schedule.run({3, 1e-5}).two_states);
  EXPECT_TRUE(states.probe.empty() && states.slow.empty());
}

TEST(HostState, ProbeReadsTheExplicitPathPerGradU) {
  bench::ExplicitPathProbe probe;
  EXPECT_GE(probe.methods.size(), 10u);  // the registry's explicit methods with plain kicks
  for (const erkn::Method& m : probe.methods) EXPECT_TRUE(m.is_explicit());
  const double ns = probe.read();
  EXPECT_GT(ns, 1.0);  // ns per grad U of a d = 1 problem, construction included
  EXPECT_LT(ns, 1e4);
}

/// A csv (write_csv's format) of one ratio per method with the given readings per round.
std::string csv_with(const char* name, const std::vector<double>& probe, double ratio) {
  const std::string path = testing::TempDir() + name;
  bench::Results r;
  for (const char* method : {"Strang", "SD9(10,6,4)"}) {
    bench::Cell c{"Duffing (P2)", method, 200, 0.01, ratio, ratio, ratio};
    c.states.probe = probe, c.states.slow.assign(probe.size(), false);
    r.cells.push_back(c);
  }
  bench::write_csv(r, path);
  return path;
}

TEST(HostState, CsvKeepsRatiosAndReadings) {
  const auto read = bench::read_csv(csv_with("a.csv", {3.5, 3.6, 5.0}, 1.25));
  ASSERT_EQ(read.count("plain,Duffing (P2),SD9(10,6,4)"), 1u);
  const bench::CsvRatio& v = read.at("plain,Duffing (P2),SD9(10,6,4)");
  EXPECT_EQ(v.ratio, 1.25);
  EXPECT_EQ(v.probe, (std::vector<double>{3.5, 3.6, 5.0}));
}

TEST(HostState, CsvQuotesFieldsWithCommas) {
  std::ifstream f(csv_with("q.csv", {3.5}, 1.25));
  std::string line;
  int rows = 0;
  while (std::getline(f, line)) {
    EXPECT_EQ(bench::csv_fields(line).size(), 5u) << line;  // (header included)
    rows += line.find("\"SD9(10,6,4)\"") != std::string::npos;
  }
  EXPECT_EQ(rows, 3);  // (plain, default, output)
  EXPECT_EQ(bench::csv_fields("a,\"b \"\"c\"\", d\",e")[1], "b \"c\", d");
  // Negative control: the name unquoted makes three fields of one.
  EXPECT_EQ(bench::csv_fields("plain,Duffing (P2),SD9(10,6,4),1.25,3.5").size(), 7u);
}

TEST(HostState, TwoRunsInDifferentStatesAreToldApart) {
  // Each run in one state throughout (its own split: one state); pooled, the runs differ.
  const auto fast = blocks(7, 7, 1, 0.02, nullptr, 5), slow = blocks(7, 7, 1, 0.02, nullptr, 6);
  std::vector<double> slow_scaled;
  for (double x : slow) slow_scaled.push_back(kSlowFactor * x);
  const auto a = bench::read_csv(csv_with("f.csv", fast, 1.0));
  const auto b = bench::read_csv(csv_with("s.csv", slow_scaled, 1.3));
  const bench::StateSplit pooled = bench::pooled_split(a, b);
  ASSERT_TRUE(pooled.two_states);
  for (const bench::Spread& s : bench::spreads(a, b, pooled)) {
    EXPECT_EQ(s.slow_before, 0);
    EXPECT_EQ(s.slow_now, 7);
    EXPECT_TRUE(s.states_differ());
  }
  // Negative control: both runs in the fast state.
  const auto c = bench::read_csv(csv_with("g.csv", blocks(7, 7, 1, 0.02, nullptr, 7), 1.3));
  const bench::StateSplit same = bench::pooled_split(a, c);
  EXPECT_FALSE(same.two_states);
  for (const bench::Spread& s : bench::spreads(a, c, same)) EXPECT_FALSE(s.states_differ());
}

}  // namespace
