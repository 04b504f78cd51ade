#include "report.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "charts.hpp"
#include "markdown.hpp"
#include "retime.hpp"
#include "summary.hpp"
#include "targets.hpp"
#include "verdict.hpp"

namespace ex {
namespace {

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  for (std::string line; std::getline(f, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

void problem_section(std::ostream& md, const ProblemResult& r) {
  const std::string key = slug(r.key);
  md << "\n## " << r.key << " — " << r.title << "\n\n"
     << "Error: max-norm of q(" << r.t_error
     << ") minus the reference. Reference: " << r.reference.method;
  if (r.reference.steps > 0)
    md << "; it agrees with the run at twice the step to " << sci(r.reference.accuracy)
       << " (max-norm)";
  md << ".\n\n| methods with the peers | error vs ∇U evaluations | error vs CPU time | energy "
        "error vs t_end |\n|---|---|---|---|\n";
  for (const ChartGroup& g : chart_groups(r.methods)) {
    const std::string stem = "charts/" + key + g.suffix;
    md << "| " << g.title << " | ![](" << stem << "_evals.png) | ![](" << stem << "_cpu.png) | ![]("
       << stem << "_energy.png) |\n";
  }
  md << "\n";
  const double h = r.methods.empty() ? 0 : r.methods.front().energy.h;
  md << "| method | kind | ∇U evals to 1e-6 | CPU ms to 1e-6 | ∇U evals to 1e-9 | CPU ms to 1e-9 "
        "| mean stage iterations (h = 1/"
     << std::lround(1 / h) << ") | max\\|H_n − H_0\\| to t = 1000 |\n"
     << "|---|---|--:|--:|--:|--:|--:|--:|\n";
  Cost peer[2] = {best_peer(r, kTolerances[0]), best_peer(r, kTolerances[1])};
  for (const MethodResult& m : r.methods) {
    md << "| " << m.name << " | " << kind_name(m);
    for (int t = 0; t < 2; ++t) {
      const Cost c = cost_to_tolerance(m.sweep, kTolerances[t]);
      std::optional<double> ms = c.cpu ? std::optional<double>(*c.cpu * 1e3) : std::nullopt;
      std::optional<double> peer_ms =
          peer[t].cpu ? std::optional<double>(*peer[t].cpu * 1e3) : std::nullopt;
      md << " | " << with_ratio(c.evals, peer[t].evals, "%.0f") << " | "
         << with_ratio(ms, peer_ms, "%.3g");
    }
    const auto its = mean_stage_iterations(m.energy.stats);
    md << " | " << (its ? fmt("%.2f", *its) : "—") << " | "
       << (m.energy.failure.empty() && !m.energy.max_error.empty() ? sci(m.energy.max_error.back())
                                                                   : "failed: " + m.energy.failure)
       << " |\n";
  }
}

void scaling_section(std::ostream& md, const ScalingResult& s) {
  md << "\n## Scaling — P1 for growing N, t ∈ [0, " << s.t_end << "]\n\n"
     << "CPU time (ms) to reach error " << sci(s.tolerances.front())
     << " (step doubled or halved from a start until the error crosses it, then interpolated). "
        "Reference per N: RKF7(8) with fixed steps in double precision (ample for this "
        "tolerance); steps, and agreement with the run at twice the step:";
  for (size_t i = 0; i < s.sizes.size(); ++i)
    md << (i ? "; " : " ") << "N = " << s.sizes[i] << ": " << s.references[i].steps << ", "
       << sci(s.references[i].accuracy);
  md << ". In parentheses: ratio to the best peer at the same N. The RKN limits are left out: "
        "like the peers without an exact linear flow they must resolve the fastest mode of M, "
        "which grows with N.\n\n";
  md << "![CPU time to 1e-6 vs N](charts/scaling.png)\n\n| method |";
  for (int n : s.sizes) md << " N = " << n << " |";
  md << "\n|---|";
  for (size_t i = 0; i < s.sizes.size(); ++i) md << "--:|";
  md << "\n";
  for (size_t l = 0; l < s.lines.size(); ++l) {
    md << "| " << s.lines[l].name << " |";
    for (size_t i = 0; i < s.sizes.size(); ++i) {
      std::optional<double> peer;
      for (size_t p = 0; p < s.lines.size(); ++p)
        if (s.lines[p].family == Family::peer)
          if (const auto c = scaling_cpu(s, p, i); c && (!peer || *c < *peer)) peer = c;
      const auto c = scaling_cpu(s, l, i);
      md << " "
         << with_ratio(c ? std::optional<double>(*c * 1e3) : std::nullopt,
                       peer ? std::optional<double>(*peer * 1e3) : std::nullopt, "%.3g")
         << " |";
    }
    md << "\n";
  }
}

void stiff_section(std::ostream& md, const std::vector<StiffResult>& stiff) {
  md << "\n## Stiff nonlinear part — sine-Gordon with U = −κ Σ cos u, N = 32\n\n"
     << "u(0) = sin(2πi/N), u'(0) = 0, error at t = " << stiff.front().result.t_error
     << ". The stiffness h²κ sits in ∇U, which no exact linear flow absorbs: explicit kicks "
        "become unstable once h²κ leaves their stability interval, implicit stages once their "
        "solver stops converging. Step sizes from a sweep (factor 2 in a quick run); "
        "“fails at h” is the smallest step size that failed (unstable or refused), “runs at h” "
        "the largest one below it that ran; the charts mark failed runs with crosses. "
        "`erkn stability` charts the (V, z) regions, z = h²·(∇²U eigenvalue), that predict "
        "these limits; the table gives their V = 0 line: the smallest z at which |tr S(0, z)| > 2 "
        "(S singular included), for the registry's methods from erkn::stability_matrix and for "
        "the splitting peers from the product of their flow and kick matrices (the other peers: "
        "—). With ∇²U = κ cos u, a run is linearly unstable once h²κ passes it (▼ in the "
        "error-vs-h charts). A run counts as failed when its error at t = 1 exceeds 100 (1 + |q|) "
        "or the runtime refuses h or cannot solve a stage; at coarse h an instability has few "
        "steps to grow, so a run past its bound may complete with a large error instead.\n";
  for (const auto& [kappa, tolerances, r] : stiff) {
    const std::string key = slug(r.key);
    md << "\n### " << r.title << "\n\nReference: " << r.reference.method << "; agreement "
       << sci(r.reference.accuracy) << ".\n\n"
       << "| methods with the peers | error vs CPU time | error vs step size |\n|---|---|---|\n";
    for (const ChartGroup& g : chart_groups(r.methods)) {
      const std::string stem = "charts/" + key + g.suffix;
      md << "| " << g.title << " | ![](" << stem << "_cpu.png) | ![](" << stem << "_h.png) |\n";
    }
    md << "\n"
       << "| method | kind | S(0, z) unstable from z = | fails at h (h²κ) | runs at h | failure "
          "| CPU ms to "
       << fmt("%.0e", tolerances[0]) << " | CPU ms to " << fmt("%.0e", tolerances[1]) << " |\n"
       << "|---|---|--:|--:|--:|---|--:|--:|\n";
    for (const MethodResult& m : r.methods) {
      Limit l = stability_limit(m.sweep);
      if (l.why.size() > 60) l.why = l.why.substr(0, 57) + "...";
      for (char& ch : l.why)
        if (ch == '|') ch = '/';
      md << "| " << m.name << " | " << kind_name(m) << " | "
         << (m.first_unstable_z ? fmt("%.3g", *m.first_unstable_z) : "—") << " | "
         << (l.failed_h ? fmt("%.3g", *l.failed_h) + " (" +
                              fmt("%.3g", *l.failed_h * *l.failed_h * kappa) + ")"
                        : "—")
         << " | " << (l.stable_h ? fmt("%.3g", *l.stable_h) : "—") << " | " << l.why;
      for (double tol : tolerances) {
        const auto c = cost_to_tolerance(m.sweep, tol).cpu, peer = best_peer(r, tol).cpu;
        md << " | "
           << with_ratio(c ? std::optional<double>(*c * 1e3) : std::nullopt,
                         peer ? std::optional<double>(*peer * 1e3) : std::nullopt, "%.3g");
      }
      md << " |\n";
    }
  }
}

// The header of results.md: the run, and how every number in it was measured.
void write_methodology(std::ostream& md, const RunInfo& info) {
  md << "# erkn — measured results\n\n"
     << "Written by `" << info.command << "` (" << info.mode << " sweep) in "
     << fmt("%.0f", info.wall_seconds) << " s (" << fmt("%.0f", info.cpu_seconds)
     << " s of CPU time) on " << cpu_model() << " (" << std::thread::hardware_concurrency()
     << " hardware threads, one used). "
     << "Do not edit: every number below comes from that run.\n\n"
     << "- **Methods**: the methods of erkn's registry that the command selects (all by default: "
        "the paper's ERKN methods and their RKN limits, erkn's explicit methods, its other "
        "implicit methods) and the peers below.";
  if (!info.identical.empty()) {
    md << " Registry methods identical to an earlier one (same kind, stages and coefficients) "
          "are run once, under the earlier name:";
    for (size_t i = 0; i < info.identical.size(); ++i) md << (i ? ", " : " ") << info.identical[i];
    md << ".";
  }
  md << "\n"
     << "- **Cost** counts every evaluation of ∇U, including each fixed-point or Newton "
        "iteration of the implicit stages; for the peers, every evaluation of the full force "
        "−Mq − ∇U(q).\n"
     << "- **CPU time** is process CPU time, the best of up to " << info.repeats
     << " repeats (a run shorter than 1 ms is timed in a batch of runs of at least 1 ms, divided "
        "by "
        "the batch size), coefficient setup included. After each scene's sweeps, the runs that "
        "decide its comparisons (the runs each summary ratio is read from, of every method "
        "within "
     << fmt("%g", kContenderMargin) << "× of its group's best) are timed again in " << info.rounds
     << " interleaved rounds, round-robin over the methods; their CPU time is the best round, "
        "and each round's own ratio (with that of the best times) gives the range shown in "
        "brackets.\n"
     << "- **Fairness**: every method, erkn's and the peers', calls the same ∇U code (the "
        "problems library's); its setup (erkn: constructing the Integrator with its default "
        "options, as a user would; a peer: its eigenbasis and flow tables) is inside every timed "
        "run; all are measured against the same reference, to the same tolerance.\n"
     << "- **To 1e-6 / 1e-9**: interpolated linearly on the log–log error curve between the two "
        "measured step sizes that first bracket the tolerance; “—” when no measured pair brackets "
        "it (never extrapolated). If the coarser run of the pair failed (unstable, or a step size "
        "the method refuses), or a measured run within the tolerance is cheaper, that run's own "
        "cost is taken. In parentheses: the ratio to the best peer at the same tolerance in this "
        "run (below 1 means cheaper than every peer).\n"
     << "- **Peers**: Störmer–Verlet (velocity form, full force); Boost.Odeint "
        "`symplectic_rkn_sb3a_mclachlan` (6 force evaluations a step as shipped) and "
        "`symplectic_rkn_sb3a_m4_mclachlan` (5); the 2-stage Gauss–Legendre method (order 4) in "
        "Nyström form, its stages solved by simplified Newton with the Jacobian −M (solved in the "
        "eigenbasis of M), started from the previous step's extrapolated stages; and the "
        "exact-flow splitting "
        "methods, which alternate the exact flow of q'' + Mq = 0 (in M's eigen coordinates: "
        "identity or real FFT) with kicks by the same ∇U code, the last kick of a step serving "
        "as the first of the next (FSAL): Strang / impulse (order 2), Blanes–Moan SRKN6b (order "
        "4, 6 ∇U a step) and SRKN14a (order 6, 14), ABA(10,6,4) of Blanes, Casas, Farrés, "
        "Laskar, Makazaga & Murua (8; error O(εh¹⁰ + ε²h⁶ + ε³h⁴) for a perturbation of size ε), "
        "the mollified impulse method of García-Archilla, Sanz-Serna & Skeel (filter sinc, "
        "order 2), the force-gradient OMF4 (4MN3F3GP) of Omelyan, Mryglod & Folk (order 4, 3 "
        "kicks with ∇(|∇U|²) = 2∇²U∇U a step) and the processed PMLF6 of Blanes, Casas & Ros as "
        "in REBOUND (order 6, 3 kicks, one modified; its processor applied at the start and to "
        "every state given out). All peers are written in experiments/, independently of the "
        "runtime.\n";
}

// summary.md beside results.md: the verdict alone.
void write_summary(const std::filesystem::path& file, const RunInfo& info,
                   const std::string& verdict) {
  const std::filesystem::path summary = file.parent_path() / "summary.md";
  std::ofstream sm(summary);
  if (!sm) throw std::runtime_error("cannot write " + summary.string());
  sm << "# erkn — summary of the measured results\n\nWritten by `" << info.command << "` ("
     << info.mode << " sweep) with [results.md](results.md), which holds every number behind it. "
     << "Do not edit.\n\n"
     << verdict;
}

}  // namespace

void write_report(const std::filesystem::path& file, const RunInfo& info,
                  const std::vector<ProblemResult>& problems,
                  const std::optional<ScalingResult>& scaling,
                  const std::vector<StiffResult>& stiff) {
  std::ofstream md(file);
  if (!md) throw std::runtime_error("cannot write " + file.string());
  write_methodology(md, info);
  const std::vector<SceneRuns> scenes = target_scenes(problems, scaling);
  const std::string verdict = verdict_markdown(scenes, stiff);
  md << "\n" << verdict << "\n" << targets_markdown(scenes) << breakdown_markdown(scenes);
  write_summary(file, info, verdict);
  for (const ProblemResult& r : problems) problem_section(md, r);
  if (scaling) scaling_section(md, *scaling);
  if (!stiff.empty()) stiff_section(md, stiff);
}

}  // namespace ex
