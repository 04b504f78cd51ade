#include "summary.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "interpolate.hpp"

namespace ex {
namespace {

std::optional<double> min_opt(const std::optional<double>& a, const std::optional<double>& b) {
  if (!a) return b;
  if (!b) return a;
  return std::min(*a, *b);
}

enum class Axis { evals, cpu, steps };

// Errors this small may differ by round-off between two codes of the same method.
constexpr double kRoundOff = 1e-9;
// Relative agreement of the errors of the same method (above round-off).
constexpr double kSameError = 1e-4;

// CPU seconds of a run: its best time, or its time in interleaved round `round` if it has one.
double cpu_of(const Measurement& m, std::optional<int> round) {
  return round && *round < int(m.round_cpu.size()) ? m.round_cpu[size_t(*round)] : m.cpu;
}

std::vector<CurvePoint> curve(const std::vector<Measurement>& ms, Axis axis,
                              std::optional<int> round = std::nullopt) {
  std::vector<CurvePoint> pts;
  for (const Measurement& m : ms)
    pts.push_back({axis == Axis::cpu     ? cpu_of(m, round)
                   : axis == Axis::evals ? double(m.stats.grad_evals)
                                         : double(m.steps),
                   m.error});
  return pts;
}

}  // namespace

Cost cost_to_tolerance(const std::vector<Measurement>& sweep, double tolerance,
                       std::optional<int> round) {
  return {ex::cost_to_tolerance(curve(sweep, Axis::evals), tolerance),
          ex::cost_to_tolerance(curve(sweep, Axis::cpu, round), tolerance),
          ex::cost_to_tolerance(curve(sweep, Axis::steps), tolerance)};
}

Cost best_peer(const ProblemResult& result, double tolerance) {
  Cost best;
  for (const MethodResult& m : result.methods) {
    if (m.family != Family::peer) continue;
    const Cost c = cost_to_tolerance(m.sweep, tolerance);
    best.evals = min_opt(best.evals, c.evals);
    best.cpu = min_opt(best.cpu, c.cpu);
  }
  return best;
}

bool in_group(const SolverTraits& t, Group group) {
  const bool peer = t.family == Family::peer;
  switch (group) {
    case Group::shipped:
      return !peer;
    case Group::paper:
      return !peer && t.from_paper;
    case Group::shipped_explicit:
      return !peer && !t.from_paper && t.is_explicit;
    case Group::shipped_other:
      return !peer && !t.from_paper && !t.is_explicit;
    case Group::peer:
      return peer;
    case Group::exact_peer:
      return peer && t.exact_linear;
    case Group::other_peer:
      return peer && !t.exact_linear;
  }
  return false;
}

std::string group_phrase(Group group) {
  switch (group) {
    case Group::shipped:
      return "the best method erkn ships";
    case Group::paper:
      return "the best method of the paper";
    case Group::shipped_explicit:
      return "the best explicit method erkn ships";
    case Group::shipped_other:
      return "the best of erkn's other implicit methods";
    case Group::peer:
      return "the best peer";
    case Group::exact_peer:
      return "the best exact-flow peer";
    case Group::other_peer:
      return "the best peer without an exact linear flow";
  }
  return "";
}

SceneRuns scene_runs(const ProblemResult& result, double tolerance) {
  SceneRuns s{result.key, tolerance, {}};
  for (const MethodResult& m : result.methods) s.runs.push_back({&m, &m.sweep});
  return s;
}

SceneRuns scene_runs(const ScalingResult& result, size_t i, double tolerance) {
  SceneRuns s{"P1 scaling, N = " + std::to_string(result.sizes[i]), tolerance, {}};
  for (const ScalingResult::Line& l : result.lines) s.runs.push_back({&l, &l.brackets[i]});
  return s;
}

Best best_of(const SceneRuns& scene, Group group, std::optional<int> round) {
  Best best;
  for (const SceneRuns::Run& r : scene.runs) {
    if (!in_group(*r.traits, group)) continue;
    const Cost cost = cost_to_tolerance(*r.measurements, scene.tolerance, round);
    if (cost.cpu && (!best.cpu || *cost.cpu < *best.cpu))
      best = {cost.cpu, r.traits->name, cost, r};
  }
  return best;
}

int timing_rounds(const SceneRuns& scene) {
  size_t n = 0;
  for (const SceneRuns::Run& r : scene.runs)
    for (const Measurement& m : *r.measurements) n = std::max(n, m.round_cpu.size());
  return int(n);
}

namespace {

// f with the best timings, and its range over the scene's interleaved timing rounds.
std::optional<Ratio> over_rounds(
    const SceneRuns& scene,
    const std::function<std::optional<double>(std::optional<int> round)>& f) {
  const auto value = f(std::nullopt);
  if (!value) return std::nullopt;
  Ratio out{*value, {}, {}};
  if (timing_rounds(scene) > 0) out.low = out.high = *value;
  for (int k = 0; k < timing_rounds(scene); ++k) {
    const auto r = f(k);
    if (!r) return Ratio{*value, {}, {}};  // a round without a ratio: no range
    out.low = std::min(*out.low, *r);
    out.high = std::max(*out.high, *r);
  }
  return out;
}

}  // namespace

std::optional<Ratio> best_ratio(const SceneRuns& scene, Group a, Group b) {
  return over_rounds(scene, [&](std::optional<int> k) {
    return ratio(best_of(scene, a, k).cpu, best_of(scene, b, k).cpu);
  });
}

std::optional<Ratio> run_ratio(const SceneRuns& scene, const SceneRuns::Run& a,
                               const SceneRuns::Run& b) {
  return over_rounds(scene, [&](std::optional<int> k) {
    return ratio(cost_to_tolerance(*a.measurements, scene.tolerance, k).cpu,
                 cost_to_tolerance(*b.measurements, scene.tolerance, k).cpu);
  });
}

bool same_method(const std::vector<Measurement>& a, const std::vector<Measurement>& b) {
  int agree = 0;
  for (const Measurement& x : a)
    for (const Measurement& y : b) {
      if (x.steps != y.steps || !x.ok() || !y.ok()) continue;
      if (std::min(x.error, y.error) < kRoundOff) continue;
      if (std::abs(x.error - y.error) > kSameError * std::max(x.error, y.error)) return false;
      ++agree;
    }
  return agree >= 2;
}

std::optional<double> mean_stage_iterations(const RunStats& stats) {
  if (stats.stage_solves == 0) return std::nullopt;
  return double(stats.stage_iterations) / double(stats.stage_solves);
}

std::optional<double> implicit_stages(const std::vector<Measurement>& runs) {
  for (const Measurement& m : runs)
    if (m.ok() && m.stats.steps > 0 && m.stats.stage_solves > 0)
      return double(m.stats.stage_solves) / double(m.stats.steps);
  return std::nullopt;
}

Limit stability_limit(const std::vector<Measurement>& sweep) {
  Limit l;
  for (const Measurement& m : sweep)  // sorted by step count: h decreasing
    if (!m.ok())
      l.failed_h = m.h, l.why = m.failure, l.stable_h.reset();
    else if (l.failed_h && !l.stable_h)
      l.stable_h = m.h;
  return l;
}

std::optional<double> scaling_cpu(const ScalingResult& result, size_t line, size_t i) {
  const auto& ms = result.lines[line].brackets[i];
  return ex::cost_to_tolerance(curve(ms, Axis::cpu), result.tolerances.front());
}

std::optional<size_t> best_line(const ScalingResult& result, Group group) {
  std::optional<size_t> first;
  for (size_t i = result.sizes.size(); i-- > 0;) {
    std::optional<size_t> best;
    std::optional<double> best_cpu;
    for (size_t l = 0; l < result.lines.size(); ++l) {
      if (!in_group(result.lines[l], group)) continue;
      if (!first) first = l;
      if (const auto c = scaling_cpu(result, l, i); c && (!best_cpu || *c < *best_cpu))
        best = l, best_cpu = c;
    }
    if (best) return best;
  }
  return first;
}

std::optional<double> ratio(const std::optional<double>& a, const std::optional<double>& b) {
  if (!a || !b || *b <= 0) return std::nullopt;
  return *a / *b;
}

}  // namespace ex
