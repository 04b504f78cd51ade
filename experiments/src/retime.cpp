#include "retime.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "interpolate.hpp"

namespace ex {
namespace {

constexpr Group kGroups[] = {Group::shipped,       Group::paper, Group::shipped_explicit,
                             Group::shipped_other, Group::peer,  Group::exact_peer,
                             Group::other_peer};

// The runs a cost to `tolerance` of `cost` is read from: the bracketing pair (without a failed
// coarser run) and any run within the tolerance that is nearly as cheap.
std::set<size_t> deciding_runs(const std::vector<Measurement>& runs, double tolerance,
                               double cost) {
  std::vector<CurvePoint> points;
  for (const Measurement& m : runs) points.push_back({m.cpu, m.error});
  std::set<size_t> out;
  const auto i = bracketing_pair(points, tolerance);
  if (!i) return out;
  if (runs[*i].ok()) out.insert(*i);
  out.insert(*i + 1);
  for (size_t j = 0; j < runs.size(); ++j)
    if (runs[j].ok() && runs[j].error <= tolerance && runs[j].cpu <= kContenderMargin * cost)
      out.insert(j);
  return out;
}

// Per line, the runs to time again.
std::vector<std::set<size_t>> contenders(const std::vector<TimedLine>& lines,
                                         const std::vector<double>& tolerances) {
  std::vector<std::set<size_t>> chosen(lines.size());
  for (double tol : tolerances) {
    SceneRuns scene{"", tol, {}};
    for (const TimedLine& l : lines) scene.runs.push_back({l.traits, l.runs});
    std::vector<double> cost(lines.size(), std::numeric_limits<double>::infinity());
    std::vector<bool> contending(lines.size(), false);
    for (size_t k = 0; k < lines.size(); ++k)
      if (const auto c = cost_to_tolerance(*lines[k].runs, tol).cpu) cost[k] = *c;
    for (Group g : kGroups)
      if (const Best best = best_of(scene, g); best.cpu)
        for (size_t k = 0; k < lines.size(); ++k)
          if (in_group(*lines[k].traits, g) && cost[k] <= kContenderMargin * *best.cpu)
            contending[k] = true;
    // A registry method that is the same method as a contending peer: the pair's ratio is the
    // runtime's overhead, worth the same care.
    for (size_t k = 0; k < lines.size(); ++k)
      for (size_t p = 0; p < lines.size() && !contending[k]; ++p)
        if (contending[p] && lines[p].traits->family == Family::peer &&
            lines[k].traits->family != Family::peer && same_method(*lines[k].runs, *lines[p].runs))
          contending[k] = true;
    for (size_t k = 0; k < lines.size(); ++k)
      if (contending[k] && std::isfinite(cost[k]))
        for (size_t i : deciding_runs(*lines[k].runs, tol, cost[k])) chosen[k].insert(i);
  }
  return chosen;
}

}  // namespace

void retime_contenders(const Problem& problem, const std::vector<TimedLine>& lines,
                       const std::vector<double>& tolerances, const TimingPolicy& timing) {
  const std::vector<std::set<size_t>> chosen = contenders(lines, tolerances);
  std::vector<size_t> order;
  for (size_t k = 0; k < lines.size(); ++k)
    if (!chosen[k].empty()) order.push_back(k);
  for (int round = 0; round < timing.rounds; ++round)
    for (size_t j = 0; j < order.size(); ++j) {
      const size_t k = order[(j + size_t(round)) % order.size()];
      for (size_t i : chosen[k]) {
        Measurement& m = (*lines[k].runs)[i];
        m.round_cpu.push_back(time_again(*lines[k].solver, problem, m, timing.round_sample));
      }
    }
  for (size_t k : order)
    for (size_t i : chosen[k]) {
      Measurement& m = (*lines[k].runs)[i];
      if (!m.round_cpu.empty()) m.cpu = *std::min_element(m.round_cpu.begin(), m.round_cpu.end());
    }
}

}  // namespace ex
