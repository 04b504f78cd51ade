// Gradient evaluations per implicit stage solve on the paper's problems P1-P3 (docs/design.md
// section 4), for every implicit method of the registry, at the step sizes that reach the errors
// 1e-6 and 1e-9 at t_error: the step count is doubled from the paper's smallest until the max-norm
// error of q(t_error) against the experiments' reference is below the tolerance. Default Options
// (stage tolerance near round-off); "newton" counts the stages the fixed-point iteration left to
// Newton; "vs tol 0" is max |q - q'| with q' from the same run with Options::tolerance = 0 (every
// stage iterated to round-off): what the stage solver's stopping adds to the error. The last two
// columns repeat both with the stage tolerance a run of n steps may spend on the target e,
// Options::tolerance = 1e-2 e / n: a first-iteration stop is proved per stage, and its error is
// systematic, so it adds up over the steps. The means are over the ERKN methods (Kind::erkn).
//
//   erkn_stage_evaluations
#include <algorithm>
#include <cstdio>
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>
#include <erkn/problems/reference.hpp>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace {

bool implicit_stages(const erkn::Method& m) {
  const int s = m.stages();
  for (int i = 0; i < s; ++i)
    if (std::string_view(m.table().closed_forms[2 * s + erkn::Coefficients::packed(i, i)]) != "0")
      return true;
  return false;
}

struct Run {
  long steps = 0;
  double error = 0;
  erkn::Statistics stats;
  Eigen::VectorXd q;
};

// The run with n steps on [0, t_error]; error +inf when it fails (unstable h, pole, no stage
// convergence).
Run run(const erkn::Method& m, const erkn::problems::Problem& p, const Eigen::VectorXd& reference,
        long n, const erkn::Options& options = {}) {
  Run r{n, std::numeric_limits<double>::infinity(), {}, {}};
  try {
    erkn::Integrator integrator(m, erkn::problems::system(p), p.t_error / double(n), p.q0, p.p0,
                                options);
    integrator.integrate(p.t_error);
    r.error = (integrator.q() - reference).cwiseAbs().maxCoeff();
    r.stats = integrator.statistics();
    r.q = integrator.q();
  } catch (const erkn::Error&) {
  }
  return r;
}

}  // namespace

int main() {
  const double tolerances[] = {1e-6, 1e-9};
  std::vector<erkn::problems::Problem> problems;
  std::vector<Eigen::VectorXd> references;
  for (const char* key : {"P1", "P2", "P3"}) {
    problems.push_back(erkn::problems::problem_by_key(key));
    const erkn::problems::Problem& p = problems.back();
    references.push_back(p.exact ? (*p.exact)(p.t_error)
                                 : erkn::problems::reference_solution(p, p.t_error, 1e-12).q);
  }
  std::printf("%-14s %-4s %6s %10s %9s %10s %12s %7s %10s %12s %10s\n", "method", "prob", "tol",
              "h", "steps", "error", "gradU/stage", "newton", "vs tol 0", "at 1e-2e/n", "vs tol 0");
  erkn::Options converged;
  converged.tolerance = 0;
  double worst[2] = {0, 0}, sum[2][2] = {}, count[2] = {};
  for (const erkn::Method& m : erkn::Method::all()) {
    if (!implicit_stages(m)) continue;
    for (size_t k = 0; k < problems.size(); ++k) {
      const erkn::problems::Problem& p = problems[k];
      long n = *std::min_element(p.paper_steps.begin(), p.paper_steps.end()) / 8;
      for (int t = 0; t < 2; ++t) {
        Run r;
        for (; n <= (1L << 20); n *= 2)
          if ((r = run(m, p, references[k], n)).error <= tolerances[t]) break;
        if (!(r.error <= tolerances[t])) {
          std::printf("%-14s %-4s %6.0e   not reached\n", std::string(m.name()).c_str(),
                      p.key.c_str(), tolerances[t]);
          continue;
        }
        const double per_stage =
            double(r.stats.gradient_evaluations) / double(r.stats.steps) / double(m.stages());
        worst[t] = std::max(worst[t], per_stage);
        const Run full = run(m, p, references[k], n, converged);
        const auto deviation = [&](const Run& x) {
          return x.q.size() && full.q.size() ? (x.q - full.q).cwiseAbs().maxCoeff()
                                             : std::numeric_limits<double>::infinity();
        };
        erkn::Options spread;
        spread.tolerance = 1e-2 * tolerances[t] / double(n);
        const Run s = run(m, p, references[k], n, spread);
        const double per_stage_spread =
            double(s.stats.gradient_evaluations) / double(n) / double(m.stages());
        if (m.kind() == erkn::Kind::erkn) {
          sum[t][0] += per_stage, sum[t][1] += per_stage_spread;
          ++count[t];
        }
        std::printf("%-14s %-4s %6.0e %10.5f %9ld %10.2e %12.3f %7ld %10.1e %12.3f %10.1e\n",
                    std::string(m.name()).c_str(), p.key.c_str(), tolerances[t],
                    p.t_error / double(n), r.steps, r.error, per_stage, r.stats.newton_fallbacks,
                    deviation(r), per_stage_spread, deviation(s));
      }
    }
  }
  std::printf("largest gradU/stage: %.3f at 1e-6, %.3f at 1e-9\n", worst[0], worst[1]);
  for (int t = 0; t < 2; ++t)
    std::printf("ERKN mean gradU/stage at %.0e: %.3f (default tolerance), %.3f (1e-2 e / n)\n",
                tolerances[t], sum[t][0] / count[t], sum[t][1] / count[t]);
}
