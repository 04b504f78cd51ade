// StageSolver's matrix-free Newton-Krylov (included by stage_newton.hpp): Newton on the stage
// equation without any d x d matrix, its norms and GMRES's dot products through the space's
// reduce (so it runs on a distributed space as on one process).
#pragma once

namespace erkn::detail {

// Newton-Krylov's storage (on first use), r and its first iterate Q: the fixed point's last
// iterate (Q_hat) when it stayed within kKeepIterate of the starting guess (it failed on a
// few slow modes near poles of abar_ii after reducing the others' error), else the guess (it
// diverged). (SERKN3s4(1), sine-Gordon N = 2048, 24 steps: 10.9 -> 7.9 grad U per fallback.)
template <class Space, class Coef>
void StageSolver<Space, Coef>::start_newton_krylov(int i) {
  start_newton(i);
  if (!krylov_) {
    KrylovWork& w = krylov_.emplace();
    for (Eigen::VectorXd* x : {&w.Qe, &w.ge}) x->resize(space_.dimension());
    w.gmres.emplace(space_.dimension(), kKrylovRestart);
  }
  const auto sums = space_.reduce(std::array{
      space_.squared_norm(first_iterate(x_.r_hat, k_.abar(i, i), x_.guess_hat)),
      space_.squared_norm(x_.Q_hat - first_iterate(x_.r_hat, k_.abar(i, i), x_.guess_hat))});
  if (!(sums[1] <= kKeepIterate * kKeepIterate * sums[0]))
    x_.Q_hat = first_iterate(x_.r_hat, k_.abar(i, i), x_.guess_hat);
  space_.inverse(x_.Q_hat, x_.Q);
}

// Newton on F for d > kDenseNewtonMaxD: each linear system J dQ = F is solved by (flexible)
// GMRES with J v = v + h^2 abar_ii(V) K v, K v a directional difference of grad U (+ M v),
// right-preconditioned in M's eigenbasis by 1 + h^2 abar_ii(v_k) sigma, sigma = w^T K w / w^T w
// the Hessian's Rayleigh quotient along the first residual w (measured by GMRES's first product,
// which is left unpreconditioned).
template <class Space, class Coef>
void StageSolver<Space, Coef>::newton_krylov(int i, Statistics& stats) {
  start_newton_krylov(i);
  double delta_old = 0, residual = 0;
  int it = 1, stalls = 0;
  bool sigma_pending = true;  // (the preconditioner is measured once per solve)
  for (; it <= options_.max_newton_iterations; ++it) {
    const int done = krylov_iteration(i, it, delta_old, stalls, residual, sigma_pending, stats);
    if (done > 0) return;
    if (done < 0) break;
  }
  not_converged(i, residual, it);
}

// One Newton-Krylov iteration: 1 when converged (G(i) set), -1 when the update is not finite,
// else 0.
template <class Space, class Coef>
int StageSolver<Space, Coef>::krylov_iteration(int i, int it, double& delta_old, int& stalls,
                                               double& residual, bool& sigma_pending,
                                               Statistics& stats) {
  NewtonWork& w = *newton_;
  KrylovWork& kw = *krylov_;
  const auto apply = [&](const auto& v, Eigen::VectorXd& Jv) {
    jacobian_times(i, v, Jv, stats);
    if (!sigma_pending) return;
    const auto sums =
        space_.reduce(std::array{space_.dot(v, kw.ge), space_.squared_physical_norm(v)});
    set_preconditioner(i, sums[0] / sums[1]);  // (v != 0: GMRES's first vector)
    sigma_pending = false;
  };
  const auto precondition = [&](const auto& v, auto&& z) {
    if (sigma_pending) {
      z = v;
      return;
    }
    w.col = v;
    space_.forward(w.col, w.col_hat);
    w.col_hat /= kw.precond;
    space_.inverse(w.col_hat, w.col);
    z = w.col;
  };
  force(x_.Q, i, stats);
  w.gU = x_.g;
  apply_abar(i, x_.g, w.F);
  w.F += x_.Q - w.r;
  const auto [norm_F, norm_Q] = norms(w.F, x_.Q);
  residual = norm_F / std::max(norm_Q, 1e-300);
  const double forcing =
      std::clamp(kLinearShare * options_.tolerance / residual, kKrylovTolerance, kMaxForcing);
  kw.gmres->solve(apply, precondition, space_, w.F, w.Q_new, forcing, kKrylovMaxIterations);
  x_.Q -= w.Q_new;
  ++stats.newton_iterations, ++stats.stage_iterations;
  const auto [norm_dQ, norm_Q_new] = norms(w.Q_new, x_.Q);
  const double delta = norm_dQ / std::max(norm_Q_new, 1e-300);
  if (!std::isfinite(delta)) return -1;
  // |Q_before - Q*| <= delta / (1 - theta): the iterate before this update may already be
  // within the tolerance, and its gradient is known (no confirming evaluation).
  if (it > 1 && delta < delta_old && delta / (1 - delta / delta_old) <= options_.tolerance) {
    x_.Q += w.Q_new;
    space_.forward(w.gU, G(i));
    return 1;
  }
  if (newton_converged(delta, delta_old, it)) {
    force(x_.Q, i, stats);
    space_.forward(x_.g, G(i));
    return 1;
  }
  check_contraction(i, "Newton-Krylov", delta, delta_old, it, stalls, residual);
  delta_old = delta;
  return 0;
}

// out = h^2 abar_ii(V) x, through the eigenbasis.
template <class Space, class Coef>
void StageSolver<Space, Coef>::apply_abar(int i, const Eigen::VectorXd& x, Eigen::VectorXd& out) {
  NewtonWork& w = *newton_;
  space_.forward(x, w.col_hat);
  w.col_hat *= k_.abar(i, i);
  space_.inverse(w.col_hat, out);
}

// Jv = v + h^2 abar_ii(V) (g(Q + e v) - g(Q)) / e, with g = grad U (+ M Q) at Q in gU.
template <class Space, class Coef>
template <class V>
void StageSolver<Space, Coef>::jacobian_times(int i, const V& v, Eigen::VectorXd& Jv,
                                              Statistics& stats) {
  KrylovWork& kw = *krylov_;
  const auto [norm_v, norm_Q] = norms(v, x_.Q);
  if (norm_v == 0) {
    Jv.setZero(space_.dimension());
    return;
  }
  const double e = std::sqrt(std::numeric_limits<double>::epsilon()) * (1 + norm_Q) / norm_v;
  kw.Qe = x_.Q + e * v;
  force(kw.Qe, i, stats);
  kw.ge = (x_.g - newton_->gU) / e;
  apply_abar(i, kw.ge, Jv);
  Jv += v;
}

// precond = 1 + h^2 abar_ii(v_k) sigma (entries near 0 replaced by 1: no division by ~0).
template <class Space, class Coef>
void StageSolver<Space, Coef>::set_preconditioner(int i, double sigma) {
  Eigen::ArrayXd& p = krylov_->precond;
  p = (Eigen::ArrayXd::Zero(space_.size()) + k_.abar(i, i)) * sigma + 1.0;
  p = (p.abs() < 1e-2).select(1.0, p);
}

}  // namespace erkn::detail
