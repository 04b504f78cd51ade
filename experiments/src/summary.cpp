#include "summary.hpp"

#include "interpolate.hpp"

namespace ex {
namespace {

std::optional<double> min_opt(const std::optional<double>& a, const std::optional<double>& b) {
  if (!a) return b;
  if (!b) return a;
  return std::min(*a, *b);
}

enum class Axis { evals, cpu, steps };

std::vector<CurvePoint> curve(const std::vector<Measurement>& ms, Axis axis) {
  std::vector<CurvePoint> pts;
  for (const Measurement& m : ms)
    pts.push_back({axis == Axis::cpu     ? m.cpu
                   : axis == Axis::evals ? double(m.stats.grad_evals)
                                         : double(m.steps),
                   m.error});
  return pts;
}

}  // namespace

Cost cost_to_tolerance(const std::vector<Measurement>& sweep, double tolerance) {
  return {ex::cost_to_tolerance(curve(sweep, Axis::evals), tolerance),
          ex::cost_to_tolerance(curve(sweep, Axis::cpu), tolerance),
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

SceneRuns scene_runs(const ScalingResult& result, size_t i) {
  SceneRuns s{"P1 scaling, N = " + std::to_string(result.sizes[i]), result.tolerance, {}};
  for (const ScalingResult::Line& l : result.lines) s.runs.push_back({&l, &l.brackets[i]});
  return s;
}

Best best_of(const SceneRuns& scene, Group group) {
  Best best;
  for (const SceneRuns::Run& r : scene.runs) {
    if (!in_group(*r.traits, group)) continue;
    const Cost cost = cost_to_tolerance(*r.measurements, scene.tolerance);
    if (cost.cpu && (!best.cpu || *cost.cpu < *best.cpu))
      best = {cost.cpu, r.traits->name, cost, r};
  }
  return best;
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
  return ex::cost_to_tolerance(curve(ms, Axis::cpu), result.tolerance);
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
