// Gradient evaluations per implicit stage solve on the paper's problems (DESIGN.md section 4),
// for every implicit method of the registry, over t in [0, 10] at step sizes that reach errors
// between about 1e-6 and 1e-9 (docs/results.md): the cost the stage solver adds to the method.
//
//   erkn_stage_evaluations
#include <cmath>
#include <cstdio>
#include <erkn/erkn.hpp>
#include <numbers>
#include <string_view>
#include <vector>

namespace {

struct Problem {
  const char* name;
  erkn::System system;
  Eigen::VectorXd q0, p0;
  std::vector<double> h;  // coarse (about 1e-6) to fine (about 1e-9)
};

std::vector<Problem> problems() {
  const int N = 32;
  const double dx = 2.0 / N, pi = std::numbers::pi;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(N), p0(N);
  col[0] = 2 / (dx * dx), col[1] = col[N - 1] = -1 / (dx * dx);
  for (int i = 0; i < N; ++i)
    p0[i] = std::sqrt(double(N)) * (0.01 + std::sin(2 * pi * (i + 1) / N));
  erkn::System p1, p2, p3;
  p1.M = erkn::Stiffness::circulant(col);
  p1.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().sin(); };
  const double k2 = 0.03 * 0.03, eps = 1e-3;
  p2.M = erkn::Stiffness::scalar(100);
  p2.gradient = [k2](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g[0] = k2 * (q[0] - 2 * q[0] * q[0] * q[0]);
  };
  p3.M = erkn::Stiffness::diagonal(Eigen::Vector2d(4, 1));
  p3.gradient = [eps](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g[0] = -eps * q[1] * q[1];
    g[1] = -2 * eps * q[0] * q[1];
  };
  return {
      {"P1", p1, Eigen::VectorXd::Constant(N, pi), p0, {1.0 / 20, 1.0 / 40, 1.0 / 100}},
      {"P2", p2, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 10), {1.0 / 4, 1.0 / 12}},
      {"P3", p3, Eigen::VectorXd::Ones(2), Eigen::VectorXd::Zero(2), {1.0 / 1.25, 1.0 / 3}}};
}

}  // namespace

int main() {
  std::printf("%-14s %-4s %10s %8s %14s %9s\n", "method", "prob", "h", "steps", "gradU/stage",
              "newton");
  double worst = 0;
  for (const erkn::Method& m : erkn::Method::all()) {
    if (m.kind() != erkn::Kind::erkn) continue;
    const int s = m.stages();
    bool explicit_method = true;
    for (int i = 0; i < s; ++i)
      explicit_method &=
          std::string_view(m.table().closed_forms[2 * s + i * (i + 1) / 2 + i]) == "0";
    if (explicit_method) continue;
    for (const Problem& pr : problems())
      for (double h : pr.h) {
        erkn::Integrator run(m, pr.system, h, pr.q0, pr.p0);
        run.integrate(10.0);
        const erkn::Statistics& st = run.statistics();
        const double per_stage = double(st.gradient_evaluations) / double(st.steps * s);
        worst = std::max(worst, per_stage);
        std::printf("%-14s %-4s %10.5f %8ld %14.3f %9ld\n", std::string(m.name()).c_str(), pr.name,
                    h, st.steps, per_stage, st.newton_fallbacks);
      }
  }
  std::printf("largest gradU/stage: %.3f\n", worst);
}
