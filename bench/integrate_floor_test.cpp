// erkn_integrate_benchmark's implicit floor (bench/integrate_floor.hpp) and what bounds an
// implicit cell (integrate_report.hpp): a cell not met is the method's through the callback
// exactly when the floor through it is above the target, met cells stay met whatever the floor
// says, a floor that disagrees with erkn's final state is never timed nor counted; the floor's
// columns take per round the faster of its two variants. Negative controls: a floor just within
// the target puts a miss on erkn; a gradient off by 1e-2 makes every floor disagree.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "integrate_report.hpp"

namespace {

using bench::FloorColumns;
using bench::ImplicitCell;
using Status = FloorColumns::Status;

ImplicitCell cell(double ratio, Status status, double floor) {
  ImplicitCell c;
  c.ratio = ratio, c.floor.status = status, c.floor.floor = floor;
  return c;
}

TEST(ImplicitBound, MissesByTheFloorAgainstTheTarget) {
  const double t = bench::kImplicitTarget;
  EXPECT_STREQ(bench::implicit_bound(cell(t, Status::timed, 1.5)), "met");  // (met is erkn's)
  EXPECT_STREQ(bench::implicit_bound(cell(t, Status::not_timed, NAN)), "met");
  EXPECT_STREQ(bench::implicit_bound(cell(1.3, Status::timed, t + 1e-3)),
               "the method through the callback");
  EXPECT_STREQ(bench::implicit_bound(cell(1.3, Status::timed, t)), "erkn");  // (control)
  EXPECT_STREQ(bench::implicit_bound(cell(1.3, Status::timed, 1.0)), "erkn");
  EXPECT_STREQ(bench::implicit_bound(cell(1.3, Status::not_timed, NAN)), "floor not timed");
  EXPECT_STREQ(bench::implicit_bound(cell(1.3, Status::disagrees, 1.5)), "floor disagrees");
}

TEST(ImplicitBound, CountsAddUp) {
  const std::vector<ImplicitCell> cells = {
      cell(1.1, Status::timed, 1.3),      cell(1.3, Status::timed, 1.25),
      cell(1.4, Status::timed, 1.1),      cell(1.25, Status::not_timed, NAN),
      cell(1.25, Status::disagrees, 1.3), cell(1.21, Status::timed, 1.21),
      cell(0.9, Status::not_timed, NAN)};
  const bench::ImplicitBounds b(cells);
  EXPECT_EQ(b.cells, 7);
  EXPECT_EQ(b.met, 2);
  EXPECT_EQ(b.missed, 5);
  EXPECT_EQ(b.by_method, 2);
  EXPECT_EQ(b.by_erkn, 1);
  EXPECT_EQ(b.unknown, 2);
}

using Stellar = bench::FloorGroupOf<2, bench::StellarGradient>;

struct Counts {
  size_t methods = 0, implicit = 0, plain_explicit = 0;
  Counts() {
    for (const erkn::Method& m : erkn::Method::all()) {
      ++methods, implicit += !m.is_explicit();
      plain_explicit += m.is_explicit() && !m.has_modified_kicks() && !m.is_processed();
    }
  }
};

std::vector<erkn::Method> registry() {
  return {erkn::Method::all().begin(), erkn::Method::all().end()};
}

// One placeholder contender per registry method (erkn's runs), then the group's.
bench::Schedule::Contenders add(Stellar& group) {
  bench::Schedule::Contenders runs(registry().size(), [] {});
  group.add(registry(), runs);
  return runs;
}

TEST(FloorGroup, AgreeingFloorsTimedWithEveryVariant) {
  Stellar group(bench::floor::stellar_scene(true), bench::StellarGradient{});
  const Counts n;
  EXPECT_EQ(add(group).size(), n.methods + 4 * n.implicit + n.plain_explicit);
}

// A gradient off by 1e-2: no floor agrees, none is timed, every miss stays unexplained.
TEST(FloorGroup, DisagreeingFloorsAreRefused) {
  bench::StellarGradient off;
  off.eps *= 1 + 1e-2;
  Stellar group(bench::floor::stellar_scene(true), off);
  const Counts n;
  const auto runs = add(group);
  EXPECT_EQ(runs.size(), n.methods + n.plain_explicit);
  const bench::Schedule::Seconds t(runs.size(), std::vector<double>(3, 1.0));
  const std::vector<double> ones(3, 1.0);
  for (size_t k = 0; k < n.implicit; ++k) {
    const FloorColumns c = group.columns(k, t, ones, ones);
    EXPECT_EQ(c.status, Status::disagrees);
    EXPECT_GT(c.diff, bench::floor::kAgree);
    ImplicitCell miss = cell(1.5, c.status, c.floor);
    EXPECT_STREQ(bench::implicit_bound(miss), "floor disagrees");
  }
}

// Seconds per run = evaluations x per-grad time: per round the faster variant is the floor.
TEST(FloorGroup, ColumnsTakeTheFasterVariantPerRound) {
  Stellar group(bench::floor::stellar_scene(true), bench::StellarGradient{});
  const auto runs = add(group);
  bench::floor::FloorRuns<2, bench::StellarGradient> r{bench::floor::stellar_scene(true), {}, {}};
  const erkn::Method& m = erkn::Method::by_name("SERKN2s3");
  size_t k = 0, first = registry().size();  // m's index among the implicit methods, its first run
  for (const erkn::Method& x : registry()) {
    if (x.is_explicit()) continue;
    if (x.name() == m.name()) break;
    ++k, first += 4;
  }
  const double ev[2] = {double(r.floor(m, r.g, bench::floor::Variant::plain)),
                        double(r.floor(m, r.g, bench::floor::Variant::carry))};
  bench::Schedule::Seconds t(runs.size(), std::vector<double>(3, 1.0));
  const double plain[3] = {2, 4, 3}, carry[3] = {3, 1, 3};  // per grad U; faster: 2, 1, 3
  for (size_t v = 0; v < 4; ++v)
    for (size_t round = 0; round < 3; ++round)
      t[first + v][round] = (v % 2 ? carry : plain)[round] * ev[v % 2];
  const std::vector<double> erkn = {4, 4, 4}, expl = {1, 2, 1};  // per grad U
  const FloorColumns c = group.columns(k, t, erkn, expl);
  EXPECT_EQ(c.status, Status::timed);
  EXPECT_LE(c.diff, bench::floor::kAgree);
  EXPECT_DOUBLE_EQ(c.floor, 2.0);       // median of 2/1, 1/2, 3/1
  EXPECT_DOUBLE_EQ(c.erkn_floor, 2.0);  // median of 4/2, 4/1, 4/3
}

}  // namespace
