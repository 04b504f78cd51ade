#include "verdict.hpp"

#include <algorithm>
#include <set>
#include <sstream>

#include "breakdown.hpp"
#include "markdown.hpp"
#include "retime.hpp"
#include "targets.hpp"

namespace ex {
namespace {

struct Case {
  std::string label;  ///< "P1 at 1e-06"
  Ratio ratio;
};

std::string label(const SceneRuns& s) { return s.scene + " at " + fmt("%.0e", s.tolerance); }

// The names of a group's methods in the run, "A, B and C".
std::string names(const SceneRuns& s, Group g) {
  std::vector<std::string> n;
  for (const SceneRuns::Run& r : s.runs)
    if (in_group(*r.traits, g)) n.push_back(r.traits->name);
  std::string out;
  for (size_t i = 0; i < n.size(); ++i)
    out += (i == 0 ? "" : i + 1 == n.size() ? " and " : ", ") + n[i];
  return out;
}

// "in 3 of 10 (P1 at 1e-06: 0.82×, ...)" or "in none of 10".
std::string cases(const std::vector<Case>& cs, size_t total) {
  if (cs.empty()) return "in none of " + std::to_string(total);
  std::string s = "in " + std::to_string(cs.size()) + " of " + std::to_string(total) + " (";
  for (size_t i = 0; i < cs.size(); ++i)
    s += (i ? "; " : "") + cs[i].label + ": " + times(cs[i].ratio);
  return s + ")";
}

// "; within the measured noise of 1× in P1 at 1e-06 and ..." for the cases whose range over the
// timing rounds reaches both sides of `target`; empty when none does.
std::string within_noise(const std::vector<Case>& cs, double target) {
  std::vector<std::string> hit;
  for (const Case& c : cs)
    if (c.ratio.straddles(target)) hit.push_back(c.label);
  if (hit.empty()) return "";
  std::string s = "; within the measured noise of " + fmt("%g", target) + "× (its range over the " +
                  "timing rounds reaches both sides) in ";
  for (size_t i = 0; i < hit.size(); ++i)
    s += (i == 0 ? "" : i + 1 == hit.size() ? " and " : ", ") + hit[i];
  return s;
}

// The run of a scene that is the same method as `run` (summary.hpp: same_method), of the other
// side (a registry method for a peer, a peer for a registry method); null when none is.
const SceneRuns::Run* twin_of(const SceneRuns& s, const SceneRuns::Run& run) {
  const bool peer = run.traits->family == Family::peer;
  for (const SceneRuns::Run& r : s.runs)
    if ((r.traits->family == Family::peer) != peer &&
        same_method(*r.measurements, *run.measurements))
      return &r;
  return nullptr;
}

// How `group`'s best fares against `against`'s best over the scenes: wins and losses.
std::string duel(const std::vector<SceneRuns>& scenes, Group group, Group against) {
  std::vector<Case> wins, losses, all;
  for (const SceneRuns& s : scenes)
    if (const auto r = best_ratio(s, group, against)) {
      (r->value <= 1 ? wins : losses).push_back({label(s), *r});
      all.push_back({label(s), *r});
    }
  const size_t n = all.size();
  return "faster " + cases(wins, n) + ", slower " + cases(losses, n) + within_noise(all, 1);
}

void comparison_table(std::ostream& md, const std::vector<SceneRuns>& scenes) {
  md << "| scene | tolerance | best paper method | / best exact-flow peer | / best other peer | "
        "best method erkn ships | / best peer |\n|---|--:|---|--:|--:|---|--:|\n";
  // "1.04× [0.95–1.12] (peer)", marked when the two are the same method.
  auto cell = [](const SceneRuns& s, Group a, Group b) {
    const auto r = best_ratio(s, a, b);
    if (!r) return std::string("—");
    const Best x = best_of(s, a), y = best_of(s, b);
    const SceneRuns::Run* twin = twin_of(s, x.run);
    return times(*r) + " (" + y.name +
           (twin && twin->traits == y.run.traits ? "; the same method: runtime overhead" : "") +
           ")";
  };
  for (const SceneRuns& s : scenes) {
    const Best paper = best_of(s, Group::paper), shipped = best_of(s, Group::shipped);
    md << "| " << s.scene << " | " << sci(s.tolerance) << " | " << (paper.cpu ? paper.name : "—")
       << " | " << cell(s, Group::paper, Group::exact_peer) << " | "
       << cell(s, Group::paper, Group::other_peer) << " | " << (shipped.cpu ? shipped.name : "—")
       << " | " << cell(s, Group::shipped, Group::peer) << " |\n";
  }
}

// " = 13.0× the steps (order 4 against 6) × 0.29× the ∇U per step (2.04 ∇U per implicit stage)
// × 1.52× the CPU per ∇U (0.91 against 0.60 µs)": the measured factors of a CPU ratio.
std::string factors(const Breakdown& b) {
  std::string s = " = " + times(b.steps) + " the steps (order " + std::to_string(b.method_order) +
                  " against " + std::to_string(b.peer_order) + ") × " + times(b.evals_per_step) +
                  " the ∇U per step";
  if (b.evals_per_stage) s += " (" + fmt("%.2f", *b.evals_per_stage) + " ∇U per implicit stage)";
  return s + " × " + times(b.cpu_per_eval) + " the CPU per ∇U (" +
         fmt("%.3g", b.method_seconds_per_eval * 1e6) + " against " +
         fmt("%.3g", b.peer_seconds_per_eval * 1e6) + " µs)";
}

// Where the best paper method stays above kPaperTarget: the measured factors of its ratio, the
// ratio at parity and the intrinsic one.
void above_target(std::ostream& md, const std::vector<SceneRuns>& scenes) {
  std::vector<std::string> rows;
  for (const SceneRuns& s : scenes) {
    const Best paper = best_of(s, Group::paper), peer = best_of(s, Group::peer);
    const auto r = best_ratio(s, Group::paper, Group::peer);
    if (!r || r->value <= kPaperTarget) continue;
    const auto b = breakdown(s, paper.run, peer);
    const auto in = smallest_intrinsic(s, Group::paper, peer);
    std::string row =
        label(s) + ": " + times(*r) + " (" + paper.name + " against " + peer.name + ")";
    if (r->straddles(kPaperTarget))
      row += ", within the measured noise of " + fmt("%g", kPaperTarget) + "×";
    if (b) row += factors(*b) + "; at CPU-per-∇U parity " + times(b->at_parity);
    if (in) {
      row += "; intrinsic " + times(*in->intrinsic) + " (" + in->method + ": " + times(in->steps) +
             " the steps at order " + std::to_string(in->method_order) + " against " +
             std::to_string(in->peer_order) + ")";
      row += *in->intrinsic > kPaperTarget
                 ? ": above " + fmt("%g", kPaperTarget) + "× even then, intrinsic to the method"
                 : ": within " + fmt("%g", kPaperTarget) +
                       "×, so the excess is CPU per ∇U and stage iterations, not the method";
    }
    rows.push_back(row);
  }
  md << "- **The best paper method within " << fmt("%g", kPaperTarget) << "× of the best peer**: ";
  if (rows.empty()) {
    md << "everywhere.\n";
    return;
  }
  md << "not in " << rows.size() << " of " << scenes.size()
     << " cases. For each: the measured ratio and its factors (steps: order and error constant; "
        "∇U per step: stages × stage iterations; CPU per ∇U: the integrator's own work and "
        "setup, all from this run); the ratio at *CPU-per-∇U parity* (the paper method's CPU "
        "time per ∇U brought to the peer's); and the *intrinsic* ratio, at parity and with "
     << fmt("%g", kEvalsPerStage)
     << " ∇U per implicit stage (the target, for the paper method best by that measure), which "
        "is owed only to order, error constant and stage count:\n";
  for (const std::string& row : rows) md << "  - " << row << "\n";
}

// Registry methods that are the same method as a peer (same errors at the same step counts):
// their CPU ratio per scene is the runtime's overhead against the hand-written step.
void same_method_lines(std::ostream& md, const std::vector<SceneRuns>& scenes) {
  std::vector<std::pair<std::string, std::vector<Case>>> pairs;  // "A against B", cases
  for (const SceneRuns& s : scenes)
    for (const SceneRuns::Run& run : s.runs) {
      if (run.traits->family == Family::peer) continue;
      const SceneRuns::Run* peer = twin_of(s, run);
      const auto r = peer ? run_ratio(s, run, *peer) : std::nullopt;
      if (!r) continue;
      const std::string pair = run.traits->name + " against " + peer->traits->name;
      auto it =
          std::find_if(pairs.begin(), pairs.end(), [&](const auto& p) { return p.first == pair; });
      if (it == pairs.end()) it = pairs.insert(pairs.end(), {pair, {}});
      it->second.push_back({label(s), *r});
    }
  if (pairs.empty()) return;
  md << "- **erkn's runtime against a hand-written peer of the same method** (the registry "
        "method and the peer reach the same errors at the same step counts, with the same ∇U "
        "code, setup included, erkn's Integrator with its defaults: the CPU ratio is runtime "
        "overhead alone):";
  for (size_t i = 0; i < pairs.size(); ++i) {
    md << (i ? ";" : "") << " " << pairs[i].first << ":";
    for (size_t j = 0; j < pairs[i].second.size(); ++j)
      md << (j ? "," : "") << " " << pairs[i].second[j].label << " "
         << times(pairs[i].second[j].ratio);
  }
  md << ".\n";
}

// How a group's methods failed in one stiff sweep: "2 of 6 failed, first at h²κ = 6.25 to 25"
// or "none of 5 failed (h²κ up to 100)"; empty when the group has no method there.
std::string failures(const StiffResult& s, Group group) {
  int n = 0, failed = 0;
  double tried = 0;
  std::optional<double> lo, hi;
  for (const MethodResult& m : s.result.methods) {
    if (!in_group(m, group)) continue;
    ++n;
    for (const Measurement& x : m.sweep) tried = std::max(tried, x.h * x.h * s.kappa);
    if (const Limit l = stability_limit(m.sweep); l.failed_h) {
      const double z = *l.failed_h * *l.failed_h * s.kappa;
      ++failed, lo = std::min(lo.value_or(z), z), hi = std::max(hi.value_or(z), z);
    }
  }
  if (n == 0) return "";
  if (failed == 0)
    return "none of " + std::to_string(n) + " failed (h²κ up to " + fmt("%.3g", tried) + ")";
  return std::to_string(failed) + " of " + std::to_string(n) +
         " failed, first at h²κ = " + fmt("%.3g", *lo) +
         (*hi > *lo ? " to " + fmt("%.3g", *hi) : "");
}

void stiff_lines(std::ostream& md, const std::vector<StiffResult>& stiff) {
  const std::pair<Group, const char*> groups[] = {
      {Group::paper, "the paper's methods"},
      {Group::shipped_explicit, "erkn's explicit methods"},
      {Group::shipped_other, "erkn's other implicit methods"},
      {Group::exact_peer, "the exact-flow peers"},
      {Group::other_peer, "the other peers"}};
  md << "- **Stiff nonlinear part** (sine-Gordon with U = −κ Σ cos u; a run fails when it is "
        "unstable or a stage solver does not converge; where each method fails and the (V, z) "
        "stability bound that predicts it are in the stiff tables of results.md):\n";
  for (const StiffResult& s : stiff) {
    md << "  - κ = " << fmt("%g", s.kappa) << ": ";
    bool first = true;
    for (const auto& [g, name] : groups)
      if (const std::string f = failures(s, g); !f.empty())
        md << (first ? "" : "; ") << name << ": " << f, first = false;
    for (double tol : s.tolerances) {
      const SceneRuns scene = scene_runs(s.result, tol);
      const Best all = best_of(scene, Group::shipped), peer = best_of(scene, Group::peer),
                 paper = best_of(scene, Group::paper);
      const Best& fastest = all.cpu && (!peer.cpu || *all.cpu < *peer.cpu) ? all : peer;
      if (!fastest.cpu) continue;
      md << "; to " << fmt("%.0e", tol) << " the fastest is " << fastest.name << " ("
         << kind_name(*fastest.run.traits) << ")";
      if (const auto r = ratio(paper.cpu, fastest.cpu); r && paper.name != fastest.name)
        md << ", the best paper method " << paper.name << " takes " << times(*r);
    }
    md << ".\n";
  }
}

}  // namespace

std::string verdict_markdown(const std::vector<SceneRuns>& scenes,
                             const std::vector<StiffResult>& stiff) {
  std::ostringstream md;
  md << "## Summary of this run\n\n"
     << "CPU time to the tolerance, setup included, best against best in the same run (below 1: "
        "faster). Generated from the measurements below; quote it rather than retyping it.";
  if (!scenes.empty() && timing_rounds(scenes.front()) > 0)
    md << " The runs that decide these ratios (each group's contenders within "
       << fmt("%g", kContenderMargin) << "× of its best) were timed again in "
       << timing_rounds(scenes.front())
       << " interleaved rounds after each scene's sweeps, round-robin, so that the methods "
          "compared see the same machine load; a CPU time is the best of the rounds, and "
          "[low–high] is the range of the ratio over the rounds (each round's ratio, and that of "
          "the "
          "best times): its measured noise.";
  md << "\n\n";
  if (!scenes.empty()) {
    comparison_table(md, scenes);
    const SceneRuns& s = scenes.front();
    md << "\n";
    if (const std::string exact = names(s, Group::exact_peer); !exact.empty())
      md << "- **The paper's implicit methods against the exact-flow peers** (" << exact
         << ", which integrate q'' + Mq = 0 exactly like the paper's methods): "
         << duel(scenes, Group::paper, Group::exact_peer) << ".\n";
    if (const std::string other = names(s, Group::other_peer); !other.empty())
      md << "- **Against the peers without an exact linear flow** (" << other
         << "): " << duel(scenes, Group::paper, Group::other_peer) << ".\n";
    md << "- **The best method erkn ships against the best peer**: "
       << duel(scenes, Group::shipped, Group::peer) << ".\n";
    same_method_lines(md, scenes);
    above_target(md, scenes);
  }
  if (!stiff.empty()) stiff_lines(md, stiff);
  return md.str();
}

}  // namespace ex
