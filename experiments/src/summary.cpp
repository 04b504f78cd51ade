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

bool in_group(Family family, bool from_paper, Group group) {
  switch (group) {
    case Group::shipped:
      return family != Family::peer;
    case Group::paper:
      return family != Family::peer && from_paper;
    case Group::peer:
      return family == Family::peer;
  }
  return false;
}

Best best_of(const ProblemResult& result, Group group, double tolerance) {
  Best best;
  for (const MethodResult& m : result.methods) {
    if (!in_group(m.family, m.from_paper, group)) continue;
    const Cost cost = cost_to_tolerance(m.sweep, tolerance);
    if (cost.cpu && (!best.cpu || *cost.cpu < *best.cpu)) best = {cost.cpu, m.name, cost};
  }
  return best;
}

Best best_of(const ScalingResult& result, Group group, size_t i) {
  Best best;
  for (size_t l = 0; l < result.lines.size(); ++l) {
    if (!in_group(result.lines[l].family, result.lines[l].from_paper, group)) continue;
    const auto c = scaling_cpu(result, l, i);
    if (c && (!best.cpu || *c < *best.cpu)) best = {c, result.lines[l].name, {}};
  }
  return best;
}

std::optional<double> mean_stage_iterations(const RunStats& stats) {
  if (stats.stage_solves == 0) return std::nullopt;
  return double(stats.stage_iterations) / double(stats.stage_solves);
}

std::optional<double> scaling_cpu(const ScalingResult& result, size_t line, size_t i) {
  const auto& ms = result.lines[line].brackets[i];
  return ex::cost_to_tolerance(curve(ms, Axis::cpu), result.tolerance);
}

std::optional<size_t> best_erkn_line(const ScalingResult& result) {
  std::optional<size_t> best;
  std::optional<double> best_cpu;
  const size_t last = result.sizes.size() - 1;
  for (size_t l = 0; l < result.lines.size(); ++l) {
    if (result.lines[l].family != Family::erkn) continue;
    const auto c = scaling_cpu(result, l, last);
    if (!best || (c && (!best_cpu || *c < *best_cpu))) best = l, best_cpu = c;
  }
  return best;
}

std::optional<double> ratio(const std::optional<double>& a, const std::optional<double>& b) {
  if (!a || !b || *b <= 0) return std::nullopt;
  return *a / *b;
}

}  // namespace ex
