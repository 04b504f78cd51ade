// The 2-stage Gauss-Legendre method (order 4) in Nystrom form, q'' = f(q) = -Mq - grad U(q):
//   Q_i = q + c_i h p + h^2 sum_j abar_ij f(Q_j),  abar = A^2,  bbar_i = b_i (1 - c_i).
// Stage solver: simplified Newton with the Jacobian -M (exact for the linear part, solved in the
// eigenbasis of M), i.e. the iteration (I + h^2 abar (x) M) Q = R - h^2 abar grad U(Q), started
// from grad U extrapolated from the previous step's stages. Every grad U evaluation is counted.
#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "block_solve.hpp"
#include "solver.hpp"

namespace ex {
namespace {

constexpr int kMaxIterations = 100;

class Gauss2 : public Solver {
 public:
  std::string name() const override { return "Gauss2 (order 4)"; }
  Family family() const override { return Family::peer; }
  bool is_explicit() const override { return false; }
  int order() const override { return 4; }

  RunResult run(const Problem& pr, double h, long steps, const Observer* obs) const override {
    const double r3 = std::sqrt(3.0);
    const double c[2] = {0.5 - r3 / 6, 0.5 + r3 / 6};
    Eigen::Matrix2d a;
    a << 0.25, 0.25 - r3 / 6, 0.25 + r3 / 6, 0.25;
    const Eigen::Matrix2d abar = a * a;
    const double b[2] = {0.5, 0.5}, bbar[2] = {0.5 * (1 - c[0]), 0.5 * (1 - c[1])};
    // Extrapolation weights: last step's stages sit at c_j - 1 relative to t_n.
    double ex[2][2];
    for (int i = 0; i < 2; ++i) {
      const double s = (c[i] - (c[0] - 1)) / (c[1] - c[0]);
      ex[i][0] = 1 - s, ex[i][1] = s;
    }
    BlockSolve block(pr.M, pr.dim(), h, abar);

    RunResult r{pr.q0, pr.p0, {}};
    const int d = pr.dim();
    Vec g1(d), g2(d), x1(d), x2(d), q1(d), q2(d), m1(d), m2(d);
    pr.grad_u(r.q, g1);
    g2 = g1;
    ++r.stats.grad_evals;
    const double h2 = h * h;
    for (long n = 0; n < steps; ++n) {
      if (n > 0) {  // extrapolate last step's stage gradients to the new nodes
        const Vec o1 = g1, o2 = g2;
        g1 = ex[0][0] * o1 + ex[0][1] * o2;
        g2 = ex[1][0] * o1 + ex[1][1] * o2;
      }
      const Vec r1 = r.q + c[0] * h * r.p, r2 = r.q + c[1] * h * r.p;
      auto solve_stages = [&] {
        x1 = r1 - h2 * (abar(0, 0) * g1 + abar(0, 1) * g2);
        x2 = r2 - h2 * (abar(1, 0) * g1 + abar(1, 1) * g2);
        block.solve(x1, x2);
      };
      solve_stages();
      double previous = std::numeric_limits<double>::infinity();
      for (int it = 1;; ++it) {
        if (it > kMaxIterations) throw std::runtime_error("Gauss2: stage iteration diverged");
        q1 = x1, q2 = x2;
        pr.grad_u(q1, g1);
        pr.grad_u(q2, g2);
        r.stats.grad_evals += 2;
        ++r.stats.stage_iterations;
        solve_stages();
        const double delta =
            std::max((x1 - q1).lpNorm<Eigen::Infinity>(), (x2 - q2).lpNorm<Eigen::Infinity>());
        const double scale = std::max(1.0, x1.lpNorm<Eigen::Infinity>());
        if (!std::isfinite(delta)) throw std::runtime_error("Gauss2: stage iteration overflow");
        if (delta <= 4 * std::numeric_limits<double>::epsilon() * scale ||
            (it > 2 && delta >= previous))
          break;
        previous = delta;
      }
      ++r.stats.stage_solves;
      pr.M.apply(x1, m1);
      pr.M.apply(x2, m2);
      const Vec f1 = -m1 - g1, f2 = -m2 - g2;
      r.q += h * r.p + h2 * (bbar[0] * f1 + bbar[1] * f2);
      r.p += h * (b[0] * f1 + b[1] * f2);
      ++r.stats.steps;
      if (obs) (*obs)(double(n + 1) * h, r.q, r.p);
    }
    return r;
  }
};

}  // namespace

std::unique_ptr<Solver> make_gauss2() { return std::make_unique<Gauss2>(); }

}  // namespace ex
