#include "report.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "charts.hpp"
#include "summary.hpp"

namespace ex {
namespace {

constexpr double kTolerances[] = {1e-6, 1e-9};

std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::string sci(double x) { return std::isfinite(x) ? fmt("%.2e", x) : "failed"; }

std::string with_ratio(const std::optional<double>& v, const std::optional<double>& peer,
                       const char* format) {
  if (!v) return "—";
  std::string s = fmt(format, *v);
  if (const auto r = ratio(v, peer)) s += " (" + fmt("%.2f", *r) + "×)";
  return s;
}

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  for (std::string line; std::getline(f, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

std::string family_name(Family f) {
  switch (f) {
    case Family::erkn:
      return "ERKN";
    case Family::rkn:
      return "RKN limit";
    case Family::peer:
      return "peer";
  }
  return "";
}

// "ratio (method)" of the best of a group against the best peer, or "—".
std::string ratio_cell(const Best& group, const Best& peer) {
  const auto q = ratio(group.cpu, peer.cpu);
  return q ? fmt("%.2f×", *q) + " (" + group.name + ")" : "—";
}

// The CPU ratio of the best paper method to the best peer as a product of measured factors:
// steps to the tolerance (order and error constant), grad U evaluations per step (stages and
// stage iterations) and CPU time per evaluation (overhead). Rows where either is missing are left
// out.
void breakdown_section(std::ostream& md, const std::vector<ProblemResult>& problems) {
  md << "\n### Where the best paper method's time goes, against the best peer\n\n"
     << "CPU ratio = steps ratio × ∇U-per-step ratio × CPU-per-∇U ratio, each read off the "
        "measured curves at the tolerance (steps: order and error constant; ∇U per step: "
        "stages × stage iterations; CPU per ∇U: the integrator's own work and setup).\n\n"
     << "| scene | tolerance | paper method | peer | CPU | steps | ∇U per step | CPU per ∇U |\n"
     << "|---|--:|---|---|--:|--:|--:|--:|\n";
  for (const ProblemResult& r : problems)
    for (double tol : kTolerances) {
      const Best a = best_of(r, Group::paper, tol), b = best_of(r, Group::peer, tol);
      const Cost &x = a.cost, &y = b.cost;
      if (!x.cpu || !x.evals || !x.steps || !y.cpu || !y.evals || !y.steps) continue;
      const double steps = *x.steps / *y.steps, evals = *x.evals / *y.evals;
      md << "| " << r.key << " | " << sci(tol) << " | " << a.name << " | " << b.name << " | "
         << fmt("%.2f×", *x.cpu / *y.cpu) << " | " << fmt("%.2f×", steps) << " | "
         << fmt("%.2f×", evals / steps) << " | "
         << fmt("%.2f×", (*x.cpu / *x.evals) / (*y.cpu / *y.evals)) << " |\n";
    }
}

std::string peer_cell(const Best& peer) {
  return peer.cpu ? fmt("%.3g ms", *peer.cpu * 1e3) + " (" + peer.name + ")" : "—";
}

void problem_section(std::ostream& md, const ProblemResult& r) {
  const std::string key = slug(r.key);
  md << "\n## " << r.key << " — " << r.title << "\n\n"
     << "Error: max-norm of q(" << r.t_error
     << ") minus the reference. Reference: " << r.reference.method;
  if (r.reference.steps > 0)
    md << "; it agrees with the run at twice the step to " << sci(r.reference.accuracy)
       << " (max-norm)";
  md << ".\n\n"
     << "![error vs ∇U evaluations](charts/" << key << "_evals.png)\n"
     << "![error vs CPU time](charts/" << key << "_cpu.png)\n"
     << "![energy error vs t_end](charts/" << key << "_energy.png)\n\n";
  const double h = r.methods.empty() ? 0 : r.methods.front().energy.h;
  md << "| method | kind | ∇U evals to 1e-6 | CPU ms to 1e-6 | ∇U evals to 1e-9 | CPU ms to 1e-9 "
        "| mean stage iterations (h = 1/"
     << std::lround(1 / h) << ") | max\\|H_n − H_0\\| to t = 1000 |\n"
     << "|---|---|--:|--:|--:|--:|--:|--:|\n";
  Cost peer[2] = {best_peer(r, kTolerances[0]), best_peer(r, kTolerances[1])};
  for (const MethodResult& m : r.methods) {
    md << "| " << m.name << " | " << family_name(m.family);
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
     << "CPU time (ms) to reach error " << sci(s.tolerance)
     << " (step doubled or halved from a start until the error crosses it, then interpolated). "
        "Reference per N: RKF7(8) with fixed steps in double precision (ample for this "
        "tolerance); steps, and agreement with the run at twice the step:";
  for (size_t i = 0; i < s.sizes.size(); ++i)
    md << (i ? "; " : " ") << "N = " << s.sizes[i] << ": " << s.references[i].steps << ", "
       << sci(s.references[i].accuracy);
  md << ". In parentheses: ratio to the best peer at the same N.\n\n";
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

// Where a sweep stops working: the smallest step size that failed, and the largest one below it
// that ran (empty when no run failed).
struct Limit {
  std::optional<double> failed_h, stable_h;
  std::string why;
};

Limit stability_limit(const std::vector<Measurement>& sweep) {
  Limit l;
  for (const Measurement& m : sweep)  // sorted by step count: h decreasing
    if (!m.ok())
      l.failed_h = m.h, l.why = m.failure, l.stable_h.reset();
    else if (l.failed_h && !l.stable_h)
      l.stable_h = m.h;
  if (l.why.size() > 60) l.why = l.why.substr(0, 57) + "...";
  for (char& ch : l.why)
    if (ch == '|') ch = '/';
  return l;
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
        "—). With ∇²U = κ cos u, a run is linearly unstable once h²κ passes it.\n";
  for (const auto& [kappa, r] : stiff) {
    const std::string key = slug(r.key);
    md << "\n### " << r.title << "\n\nReference: " << r.reference.method << "; agreement "
       << sci(r.reference.accuracy) << ".\n\n"
       << "![error vs CPU time](charts/" << key << "_cpu.png)\n"
       << "![error vs step size](charts/" << key << "_h.png)\n\n"
       << "| method | kind | S(0, z) unstable from z = | fails at h (h²κ) | runs at h | failure "
          "| CPU ms to 1e-3 | CPU ms to 1e-6 |\n"
       << "|---|---|--:|--:|--:|---|--:|--:|\n";
    const double tolerances[] = {1e-3, 1e-6};
    for (const MethodResult& m : r.methods) {
      const Limit l = stability_limit(m.sweep);
      md << "| " << m.name << " | " << family_name(m.family) << " | "
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

}  // namespace

std::string targets_markdown(const std::vector<ProblemResult>& problems,
                             const std::optional<ScalingResult>& scaling) {
  std::ostringstream md;
  md << "## Targets (issue 9): CPU time to the tolerance, setup included, same run\n\n"
     << "(a) the best method erkn ships (every method of its registry) and (b) the best method "
        "of the source paper (the registry's methods whose source is the paper) against the best "
        "peer.\n\n"
     << "| scene | tolerance | best peer | (a) best erkn / best peer | (b) best paper / best peer "
        "|\n|---|--:|---|---|---|\n";
  auto row = [&md](const std::string& scene, double tol, const Best& shipped, const Best& paper,
                   const Best& peer) {
    md << "| " << scene << " | " << sci(tol) << " | " << peer_cell(peer) << " | "
       << ratio_cell(shipped, peer) << " | " << ratio_cell(paper, peer) << " |\n";
  };
  for (const ProblemResult& r : problems)
    for (double tol : kTolerances)
      row(r.key, tol, best_of(r, Group::shipped, tol), best_of(r, Group::paper, tol),
          best_of(r, Group::peer, tol));
  for (size_t i = 0; scaling && i < scaling->sizes.size(); ++i)
    row("P1 scaling, N = " + std::to_string(scaling->sizes[i]), scaling->tolerance,
        best_of(*scaling, Group::shipped, i), best_of(*scaling, Group::paper, i),
        best_of(*scaling, Group::peer, i));
  return md.str();
}

void write_report(const std::filesystem::path& file, const RunInfo& info,
                  const std::vector<ProblemResult>& problems,
                  const std::optional<ScalingResult>& scaling,
                  const std::vector<StiffResult>& stiff) {
  std::ofstream md(file);
  if (!md) throw std::runtime_error("cannot write " + file.string());
  md << "# erkn — measured results\n\n"
     << "Written by `" << info.command << "` (" << info.mode << " sweep) in "
     << fmt("%.0f", info.wall_seconds) << " s on " << cpu_model() << " ("
     << std::thread::hardware_concurrency() << " hardware threads, one used). "
     << "Do not edit: every number below comes from that run.\n\n"
     << "- **Cost** counts every evaluation of ∇U, including each fixed-point or Newton "
        "iteration of the implicit stages; for the peers, every evaluation of the full force "
        "−Mq − ∇U(q).\n"
     << "- **CPU time** is process CPU time, the best of up to " << info.repeats
     << " repeats (a run shorter than 1 ms is timed in a batch of runs of at least 1 ms, divided "
        "by "
        "the batch size), coefficient setup included.\n"
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
        "Laskar, Makazaga & Murua (8; error O(εh¹⁰ + ε²h⁶ + ε³h⁴) for a perturbation of size ε) "
        "and the mollified impulse method of García-Archilla, Sanz-Serna & Skeel (filter sinc, "
        "order 2). All peers are written in experiments/, independently of the runtime.\n";
  md << "\n" << targets_markdown(problems, scaling);
  breakdown_section(md, problems);
  for (const ProblemResult& r : problems) problem_section(md, r);
  if (scaling) scaling_section(md, *scaling);
  if (!stiff.empty()) stiff_section(md, stiff);
}

}  // namespace ex
