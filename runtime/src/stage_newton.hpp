// StageSolver's Newton fallbacks (included by stage_solver.hpp): on F(Q) = Q - r_i + h^2
// abar_ii(V) g(Q), Jacobian I + h^2 abar_ii(V) (Hessian [+ M for RKN]); a dense LU up to
// kDenseNewtonMaxD unknowns in one process, matrix-free Newton-Krylov beyond it and on every
// distributed space.
#pragma once

namespace erkn::detail {

// Newton's workspace (on first use) and r, Q from the starting guess.
template <class Space, class Coef>
void StageSolver<Space, Coef>::start_newton(int i) {
  const Eigen::Index d = space_.dimension();
  if (!newton_) {
    NewtonWork& w = newton_.emplace();
    for (Eigen::VectorXd* x : {&w.r, &w.F, &w.gU, &w.col, &w.Q_new}) x->resize(d);
    w.col_hat.resize(space_.size());
  }
  if constexpr (Space::kDenseNewton) {
    NewtonWork& w = *newton_;
    if (w.J.rows() != d && space_.dimension() <= kDenseNewtonMaxD) {
      w.J.resize(d, d);
      w.H.resize(d, d);
      w.lu = Eigen::PartialPivLU<Eigen::MatrixXd>(d);
      if (method_.kind() == Kind::rkn) w.M_dense = system_.M.to_dense(d);
    }
  }
  space_.inverse(x_.r_hat, newton_->r);
  (void)i;
}

// Dense Newton from the starting guess.
template <class Space, class Coef>
void StageSolver<Space, Coef>::newton(int i, Statistics& stats) {
  start_newton(i);
  NewtonWork& w = *newton_;
  x_.Q_hat = first_iterate(x_.r_hat, k_.abar(i, i), x_.guess_hat);
  space_.inverse(x_.Q_hat, x_.Q);
  double delta_old = 0, residual = 0;
  int it = 1, stalls = 0;
  for (; it <= options_.max_newton_iterations; ++it) {
    gradient(x_.Q, w.gU, i, stats);
    x_.g = w.gU;
    space_.add_MQ(x_.Q, x_.g);
    space_.forward(x_.g, G(i));
    x_.Q_hat = k_.abar(i, i) * G(i);
    space_.inverse(x_.Q_hat, w.F);
    w.F += x_.Q - w.r;
    residual = w.F.norm() / std::max(x_.Q.norm(), 1e-300);
    jacobian(i, stats);
    w.lu.compute(w.J);
    w.Q_new = w.lu.solve(w.F);
    x_.Q -= w.Q_new;
    ++stats.newton_iterations, ++stats.stage_iterations;
    const double delta = w.Q_new.norm() / std::max(x_.Q.norm(), 1e-300);
    if (!std::isfinite(delta)) break;  // the Jacobian is singular
    if (newton_converged(delta, delta_old, it)) {
      // h^2 abar_ii |Hessian| may be large here, so G(i) must be the gradient at the final Q.
      force(x_.Q, i, stats);
      space_.forward(x_.g, G(i));
      return;
    }
    check_contraction(i, "Newton", delta, delta_old, it, stalls, residual);
    delta_old = delta;
  }
  not_converged(i, residual, it);
}

// The stop of both Newton solvers: iteration it (1-based) changed Q by delta (relative), the
// one before by delta_old; converged when the contraction theta proves the tolerance or the
// iteration stagnates at round-off.
template <class Space, class Coef>
bool StageSolver<Space, Coef>::newton_converged(double delta, double delta_old, int it) const {
  const double theta = it > 1 ? delta / delta_old : 1;
  return delta == 0 || (theta < 1 && theta / (1 - theta) * delta <= options_.tolerance) ||
         (it > 1 && theta >= 1 && delta <= options_.roundoff_level);
}

// Fails fast (instead of running out of iterations) once kMaxStalls successive iterations
// changed Q by at least as much as the one before them, above Options::roundoff_level: such an
// iteration sits at its own noise floor (round-off of F, directional differences) or diverges.
template <class Space, class Coef>
void StageSolver<Space, Coef>::check_contraction(int i, const char* solver, double delta,
                                                 double delta_old, int it, int& stalls,
                                                 double residual) const {
  stalls = it > 1 && delta >= delta_old ? stalls + 1 : 0;
  if (stalls < kMaxStalls) return;
  not_converged(i, residual, it,
                std::string(": ") + solver + " stopped contracting (relative change " +
                    format(delta, 3) + " in the last of " + std::to_string(kMaxStalls) +
                    " iterations without contraction, above Options::roundoff_level = " +
                    format(options_.roundoff_level, 3) + ")");
}

template <class Space, class Coef>
void StageSolver<Space, Coef>::not_converged(int i, double residual, int iterations,
                                             const std::string& why) const {
  throw Error("step " + std::to_string(at_->step) + " at t = " + format(at_->t) + ": stage " +
              std::to_string(i + 1) + " of " + std::string(method_.name()) +
              " did not converge (fixed-point iteration failed; Newton left a relative residual " +
              format(residual, 3) + " after " +
              std::to_string(std::min(iterations, options_.max_newton_iterations)) + " iterations" +
              why + "); the state is unchanged");
}

// J = I + h^2 abar_ii(V) K with K the Hessian of U (user's or finite differences) [+ M].
template <class Space, class Coef>
void StageSolver<Space, Coef>::jacobian(int i, Statistics& stats) {
  NewtonWork& w = *newton_;
  const Eigen::Index d = space_.dimension();
  if (system_.hessian) {
    system_.hessian(x_.Q, w.H);
    ++stats.hessian_evaluations;
    if (w.H.rows() != d || w.H.cols() != d || !w.H.allFinite())
      throw Error("the Hessian callback returned a non-finite value or a size other than " +
                  std::to_string(d) + "x" + std::to_string(d) + " at step " +
                  std::to_string(at_->step));
  } else {
    for (Eigen::Index j = 0; j < d; ++j) {
      const double saved = x_.Q[j], step = 1e-7 * std::max(1.0, std::abs(saved));
      x_.Q[j] = saved + step;
      gradient(x_.Q, w.col, i, stats);
      x_.Q[j] = saved;
      w.H.col(j) = (w.col - w.gU) / step;
    }
  }
  if (method_.kind() == Kind::rkn) w.H += w.M_dense;
  for (Eigen::Index j = 0; j < d; ++j) {
    w.col = w.H.col(j);
    space_.forward(w.col, w.col_hat);
    w.col_hat *= k_.abar(i, i);
    space_.inverse(w.col_hat, w.col);
    w.J.col(j) = w.col;
  }
  w.J.diagonal().array() += 1.0;
}

}  // namespace erkn::detail

#include "stage_newton_krylov.hpp"
