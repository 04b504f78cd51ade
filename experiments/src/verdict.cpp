#include "verdict.hpp"

#include <algorithm>
#include <set>
#include <sstream>

#include "breakdown.hpp"
#include "markdown.hpp"
#include "targets.hpp"

namespace ex {
namespace {

struct Case {
  std::string label;  ///< "P1 at 1e-06"
  double ratio;
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

// How `group`'s best fares against `against`'s best over the scenes: wins and losses.
std::string duel(const std::vector<SceneRuns>& scenes, Group group, Group against) {
  std::vector<Case> wins, losses;
  for (const SceneRuns& s : scenes) {
    const auto r = ratio(best_of(s, group).cpu, best_of(s, against).cpu);
    if (r) (*r <= 1 ? wins : losses).push_back({label(s), *r});
  }
  const size_t n = wins.size() + losses.size();
  return "faster " + cases(wins, n) + ", slower " + cases(losses, n);
}

void comparison_table(std::ostream& md, const std::vector<SceneRuns>& scenes) {
  md << "| scene | tolerance | best paper method | / best exact-flow peer | / best other peer | "
        "best method erkn ships | / best peer |\n|---|--:|---|--:|--:|---|--:|\n";
  auto cell = [](const Best& a, const Best& b) {
    const auto r = ratio(a.cpu, b.cpu);
    return r ? times(*r) + " (" + b.name + ")" : std::string("—");
  };
  for (const SceneRuns& s : scenes) {
    const Best paper = best_of(s, Group::paper), shipped = best_of(s, Group::shipped);
    md << "| " << s.scene << " | " << sci(s.tolerance) << " | " << (paper.cpu ? paper.name : "—")
       << " | " << cell(paper, best_of(s, Group::exact_peer)) << " | "
       << cell(paper, best_of(s, Group::other_peer)) << " | " << (shipped.cpu ? shipped.name : "—")
       << " | " << cell(shipped, best_of(s, Group::peer)) << " |\n";
  }
}

// Where the best paper method stays above kPaperTarget: the ratio at parity and the intrinsic one.
void above_target(std::ostream& md, const std::vector<SceneRuns>& scenes) {
  std::vector<std::string> rows;
  for (const SceneRuns& s : scenes) {
    const Best paper = best_of(s, Group::paper), peer = best_of(s, Group::peer);
    const auto r = ratio(paper.cpu, peer.cpu);
    if (!r || *r <= kPaperTarget) continue;
    const auto b = breakdown(s, paper.run, peer);
    const auto in = smallest_intrinsic(s, Group::paper, peer);
    std::string row =
        label(s) + ": " + times(*r) + " (" + paper.name + " against " + peer.name + ")";
    if (b) row += "; at CPU-per-∇U parity " + times(b->at_parity);
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
     << " cases. For each: the measured ratio; the ratio at *CPU-per-∇U parity* (the paper "
        "method's CPU time per ∇U brought to the peer's); and the *intrinsic* ratio, at parity "
        "and with "
     << fmt("%g", kEvalsPerStage)
     << " ∇U per implicit stage (for the paper method best by that measure), which is owed only "
        "to order, error constant and stage count:\n";
  for (const std::string& row : rows) md << "  - " << row << "\n";
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
        "faster). Generated from the measurements below; quote it rather than retyping it.\n\n";
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
    above_target(md, scenes);
  }
  if (!stiff.empty()) stiff_lines(md, stiff);
  return md.str();
}

}  // namespace ex
