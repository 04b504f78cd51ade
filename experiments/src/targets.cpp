#include "targets.hpp"

#include <sstream>

#include "breakdown.hpp"
#include "markdown.hpp"

namespace ex {
namespace {

// "ratio (method)" of the best of a group against the best peer, or "—".
std::string ratio_cell(const Best& group, const Best& peer) {
  const auto q = ratio(group.cpu, peer.cpu);
  return q ? times(*q) + " (" + group.name + ")" : "—";
}

std::string peer_cell(const Best& peer) {
  return peer.cpu ? fmt("%.3g ms", *peer.cpu * 1e3) + " (" + peer.name + ")" : "—";
}

}  // namespace

std::vector<SceneRuns> target_scenes(const std::vector<ProblemResult>& problems,
                                     const std::optional<ScalingResult>& scaling) {
  std::vector<SceneRuns> scenes;
  for (const ProblemResult& r : problems)
    for (double tol : kTolerances) scenes.push_back(scene_runs(r, tol));
  for (size_t i = 0; scaling && i < scaling->sizes.size(); ++i)
    scenes.push_back(scene_runs(*scaling, i));
  return scenes;
}

std::string targets_markdown(const std::vector<SceneRuns>& scenes) {
  std::ostringstream md;
  md << "## Targets (issue 9): CPU time to the tolerance, setup included, same run\n\n"
     << "(a) the best method erkn ships (every method of its registry) and (b) the best method "
        "of the source paper (the registry's methods whose source is the paper) against the best "
        "peer. Targets: (a) ≤ 1.0 on P1-P3 and at N = 512 and 2048; (b) ≤ "
     << fmt("%g", kPaperTarget) << " everywhere.\n\n"
     << "| scene | tolerance | best peer | (a) best erkn / best peer | (b) best paper / best peer "
        "|\n|---|--:|---|---|---|\n";
  for (const SceneRuns& s : scenes) {
    const Best peer = best_of(s, Group::peer);
    md << "| " << s.scene << " | " << sci(s.tolerance) << " | " << peer_cell(peer) << " | "
       << ratio_cell(best_of(s, Group::shipped), peer) << " | "
       << ratio_cell(best_of(s, Group::paper), peer) << " |\n";
  }
  return md.str();
}

std::string breakdown_markdown(const std::vector<SceneRuns>& scenes) {
  std::ostringstream md;
  md << "\n### Where the best paper method's time goes, against the best peer\n\n"
     << "CPU ratio = steps ratio × ∇U-per-step ratio × CPU-per-∇U ratio, each read off the "
        "measured curves at the tolerance (steps: order and error constant; ∇U per step: "
        "stages × stage iterations; CPU per ∇U: the integrator's own work and setup). "
        "*At parity*: the ratio if the paper method's CPU time per ∇U were the peer's (steps × "
        "∇U per step). *Intrinsic*: at parity and with every implicit stage solved in "
     << fmt("%g", kEvalsPerStage) << " ∇U evaluations (steps ratio × " << fmt("%g", kEvalsPerStage)
     << " × stages / the peer's ∇U per step), for the paper method with the smallest such ratio "
        "(named when it is not the fastest one): what is left is owed to order, error constant "
        "and stage count, not to the implementation.\n\n"
     << "| scene | tolerance | paper method (order) | peer (order) | CPU | steps | ∇U per step | "
        "CPU per ∇U | ∇U per stage | at parity | intrinsic |\n"
     << "|---|--:|---|---|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const SceneRuns& s : scenes) {
    const Best paper = best_of(s, Group::paper), peer = best_of(s, Group::peer);
    if (!paper.run.traits) continue;
    const auto b = breakdown(s, paper.run, peer);
    if (!b) continue;
    const auto in = smallest_intrinsic(s, Group::paper, peer);
    std::string intrinsic = in ? times(*in->intrinsic) : "—";
    if (in && in->method != b->method) intrinsic += " (" + in->method + ")";
    md << "| " << s.scene << " | " << sci(s.tolerance) << " | " << b->method << " ("
       << b->method_order << ") | " << b->peer << " (" << b->peer_order << ") | " << times(b->cpu)
       << " | " << times(b->steps) << " | " << times(b->evals_per_step) << " | "
       << times(b->cpu_per_eval) << " | "
       << (b->evals_per_stage ? fmt("%.2f", *b->evals_per_stage) : "—") << " | "
       << times(b->at_parity) << " | " << intrinsic << " |\n";
  }
  return md.str();
}

}  // namespace ex
