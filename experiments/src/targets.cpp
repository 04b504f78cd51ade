#include "targets.hpp"

#include <sstream>

#include "breakdown.hpp"
#include "markdown.hpp"

namespace ex {
namespace {

// "ratio [range] (method)" of the best of a group against the best peer, or "—"; marked when the
// range over the timing rounds reaches both sides of the target.
std::string ratio_cell(const SceneRuns& s, Group group, double target) {
  const auto q = best_ratio(s, group, Group::peer);
  if (!q) return "—";
  return times(*q) + " (" + best_of(s, group).name + ")" +
         (q->straddles(target) ? ", within noise of " + fmt("%g", target) + "×" : "");
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
    for (double tol : scaling->tolerances) scenes.push_back(scene_runs(*scaling, i, tol));
  return scenes;
}

std::string targets_markdown(const std::vector<SceneRuns>& scenes) {
  std::ostringstream md;
  md << "## Targets (issue 9): CPU time to the tolerance, setup included, same run\n\n"
     << "(a) the best method erkn ships (every method of its registry) and (b) the best method "
        "of the source paper (the registry's methods whose source is the paper) against the best "
        "peer. Targets: (a) ≤ 1.0 on P1-P3 and at N = 512 and 2048; (b) ≤ "
     << fmt("%g", kPaperTarget)
     << " everywhere. In brackets: the ratio's range over the interleaved timing rounds (its "
        "measured noise), where the deciding runs were timed again.\n\n"
     << "| scene | tolerance | best peer | (a) best erkn / best peer | (b) best paper / best peer "
        "|\n|---|--:|---|---|---|\n";
  for (const SceneRuns& s : scenes) {
    const Best peer = best_of(s, Group::peer);
    md << "| " << s.scene << " | " << sci(s.tolerance) << " | " << peer_cell(peer) << " | "
       << ratio_cell(s, Group::shipped, 1) << " | " << ratio_cell(s, Group::paper, kPaperTarget)
       << " |\n";
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
  md << paper_methods_markdown(scenes);
  return md.str();
}

std::string paper_methods_markdown(const std::vector<SceneRuns>& scenes) {
  std::ostringstream md;
  md << "\n### Every paper method against the best peer: measured factors\n\n"
     << "Per scene and tolerance, each method of the paper that reaches the tolerance against "
        "the best peer, with the same factors as above, each measured in this run: ∇U "
        "evaluations per implicit stage (stage iterations included) and CPU time per ∇U "
        "evaluation (setup included) of the method and of the peer.\n\n"
     << "| scene | tolerance | paper method (order) | peer (order) | CPU | steps | ∇U per step "
        "| ∇U per stage | µs per ∇U (peer) | CPU per ∇U | at parity | intrinsic |\n"
     << "|---|--:|---|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const SceneRuns& s : scenes) {
    const Best peer = best_of(s, Group::peer);
    for (const SceneRuns::Run& run : s.runs) {
      if (!in_group(*run.traits, Group::paper)) continue;
      const auto b = breakdown(s, run, peer);
      if (!b) continue;
      md << "| " << s.scene << " | " << sci(s.tolerance) << " | " << b->method << " ("
         << b->method_order << ") | " << b->peer << " (" << b->peer_order << ") | " << times(b->cpu)
         << " | " << times(b->steps) << " | " << times(b->evals_per_step) << " | "
         << (b->evals_per_stage ? fmt("%.2f", *b->evals_per_stage) : "—") << " | "
         << fmt("%.3g", b->method_seconds_per_eval * 1e6) << " ("
         << fmt("%.3g", b->peer_seconds_per_eval * 1e6) << ") | " << times(b->cpu_per_eval) << " | "
         << times(b->at_parity) << " | " << (b->intrinsic ? times(*b->intrinsic) : "—") << " |\n";
    }
  }
  return md.str();
}

}  // namespace ex
