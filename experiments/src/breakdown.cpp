#include "breakdown.hpp"

namespace ex {

std::optional<Breakdown> breakdown(const SceneRuns& scene, const SceneRuns::Run& method,
                                   const Best& peer) {
  if (!peer.run.traits) return std::nullopt;
  const Cost x = cost_to_tolerance(*method.measurements, scene.tolerance), &y = peer.cost;
  if (!x.cpu || !x.evals || !x.steps || !y.cpu || !y.evals || !y.steps) return std::nullopt;
  Breakdown b;
  b.method = method.traits->name;
  b.peer = peer.name;
  b.method_order = method.traits->order;
  b.peer_order = peer.run.traits->order;
  b.cpu = *x.cpu / *y.cpu;
  b.steps = *x.steps / *y.steps;
  b.evals_per_step = (*x.evals / *x.steps) / (*y.evals / *y.steps);
  b.method_seconds_per_eval = *x.cpu / *x.evals;
  b.peer_seconds_per_eval = *y.cpu / *y.evals;
  b.cpu_per_eval = b.method_seconds_per_eval / b.peer_seconds_per_eval;
  b.at_parity = b.steps * b.evals_per_step;
  if (const auto s = implicit_stages(*method.measurements)) {
    b.evals_per_stage = (*x.evals / *x.steps) / *s;
    b.intrinsic = b.steps * kEvalsPerStage * *s / (*y.evals / *y.steps);
  }
  return b;
}

std::optional<Breakdown> smallest_intrinsic(const SceneRuns& scene, Group group, const Best& peer) {
  std::optional<Breakdown> best;
  for (const SceneRuns::Run& r : scene.runs) {
    if (!in_group(*r.traits, group)) continue;
    const auto b = breakdown(scene, r, peer);
    if (b && b->intrinsic && (!best || *b->intrinsic < *best->intrinsic)) best = b;
  }
  return best;
}

}  // namespace ex
