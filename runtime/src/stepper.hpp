// The step of eq. (d) for methods with implicit stages, generic over M's eigenbasis (Transform)
// and the coefficient type (Coef). Stages run in eigen coordinates; gradients are evaluated in
// physical coordinates. D: the dimension when it is a compile-time constant (tiny systems with
// M's identity eigenbasis: the stage arrays then live inside the stepper and every pass over them
// unrolls). Explicit methods step in explicit_stepper.hpp.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "compensated_sum.hpp"
#include "erkn/error.hpp"
#include "erkn/integrator.hpp"
#include "format.hpp"
#include "gmres.hpp"
#include "m_operator.hpp"
#include "stage_checks.hpp"
#include "step_coefficients.hpp"
#include "stepper_base.hpp"

namespace erkn::detail {

template <class Transform, class Coef, int D = Eigen::Dynamic>
class Stepper final : public StepperBase {
  using Spectral = typename Transform::Spectral;
  using Scalar = typename Spectral::Scalar;
  static constexpr bool kFixed = D != Eigen::Dynamic;
  static_assert(!kFixed || std::is_same_v<Transform, IdentityTransform>,
                "a fixed dimension needs the identity basis");
  // One array in eigen coordinates (aligned when stride_ keeps it so: in the dynamic storage).
  using Array = std::conditional_t<kFixed, Eigen::Array<Scalar, D, 1>, Spectral>;
  using SpectralMap = Eigen::Map<Array, kFixed ? Eigen::Unaligned : Eigen::AlignedMax>;
  // The arrays' storage: one allocation, or (fixed dimension) inside the stepper, sized for
  // kMaxStages.
  static constexpr int kSlots = 11;  // (the arrays before the stage gradients)
  // Steps back whose stage gradients the starting values extrapolate from. One: three predicted
  // better at fine h on P1-P3, but their higher degrees let the modes with large abar_ii of P1 at
  // N = 2048 diverge (SERKN3s4(1), h = 1/32: 9.4 evaluations per stage and 23 Newton fallbacks
  // instead of 3.8, 7).
  static constexpr int kHistory = 1;
  using Storage = std::conditional_t<
      kFixed, std::array<Scalar, (kSlots + (kHistory + 1) * kMaxStages) * std::max(D, 1)>,
      Spectral>;

 public:
  /// lambda: M's eigenvalues ({0} for RKN methods, whose force then includes -M q).
  Stepper(const Method& method, System system, double h, const Options& options,
          Transform transform, const Eigen::VectorXd& lambda, Eigen::Index d)
      : method_(method),
        system_(std::move(system)),
        options_(options),
        rkn_(method.kind() == Kind::rkn),
        d_(d),
        s_(method.stages()),
        transform_(std::move(transform)),
        M_(system_.M, d),
        m_(transform_.spectral_size(d)),
        stride_(kFixed ? D : aligned_stride<Scalar>(m_)),
        spectral_(zeros(s_, stride_)),
        q_hat_(slot(0), m_),
        p_hat_(slot(1), m_),
        eq_hat_(slot(2), m_),
        ep_hat_(slot(3), m_),
        qw_hat_(slot(4), m_),
        pw_hat_(slot(5), m_),
        r_hat_(slot(6), m_),
        Q_hat_(slot(7), m_),
        Q_hat_new_(slot(8), m_),
        guess_hat_(slot(9), m_),
        g_first_hat_(slot(10), m_) {
    for (int age = 0; age <= kHistory; ++age) steps_[age] = slot(kSlots + age * s_);
    for (Eigen::VectorXd* x : {&Q_, &g_}) x->setZero(d);
    if (rkn_) Mq_.setZero(d), set_m_diagonal();
    k_.emplace(method, h, lambda);
    for (int i = 0; i < s_; ++i) {
      const auto ratio = [&](const auto& num) { return max_ratio(num, k_->abar(i, i)); };
      weight_[i] = std::max({1.0, ratio(k_->h2bbar(i)), ratio(k_->hb(i) * h)});
    }
    weights_.assign(size_t(s_) * ((kHistory + 1) * s_) * ((kHistory + 1) * s_), 0.0);
    for (int i = 0; i < s_; ++i) set_nodes(i);
  }

  Stepper(const Stepper&) = delete;  // (the maps view its own buffers)
  Stepper& operator=(const Stepper&) = delete;

  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p) override {
    transform_.forward(q, q_hat_);
    transform_.forward(p, p_hat_);
    eq_hat_.setZero();
    ep_hat_.setZero();
    history_ = 0;
    adapt_wait_.fill(1);
    adapt_interval_.fill(1);
  }

  void get_state(Eigen::VectorXd& q, Eigen::VectorXd& p) override {
    transform_.inverse(q_hat_, q);
    transform_.inverse(p_hat_, p);
  }

  void step(long step_number, double t, Statistics& stats) override {
    step_number_ = step_number;
    t_ = t;
    // The step counts into its own record, added to stats once it has succeeded (a failed step
    // counts nothing).
    Statistics counts;
    implicit_step(counts);
    stats.gradient_evaluations += counts.gradient_evaluations;
    stats.hessian_evaluations += counts.hessian_evaluations;
    stats.stage_iterations += counts.stage_iterations;
    stats.newton_fallbacks += counts.newton_fallbacks;
    stats.newton_iterations += counts.newton_iterations;
    Scalar* const oldest = steps_[kHistory];  // (rotated by hand: std::rotate was a call)
    for (int age = kHistory; age > 0; --age) steps_[age] = steps_[age - 1];
    steps_[0] = oldest;
    history_ = std::min(history_ + 1, kHistory);
    ++stats.steps;
  }

  void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) override { M_.apply(x, y); }
  System& system() override { return system_; }

 private:
  static Storage zeros(int s, Eigen::Index stride) {
    if constexpr (kFixed)
      return Storage{};
    else
      return Spectral::Zero((kSlots + (kHistory + 1) * s) * stride);
  }

  // |inverse(y)|^2 (orthonormal eigenbases: the eigen coordinates' own, without a square root).
  template <class Y>
  double squared_norm(const Y& y) const {
    if constexpr (std::is_same_v<Transform, IdentityTransform> ||
                  std::is_same_v<Transform, OrthogonalTransform> ||
                  std::is_same_v<Transform, FourierBasisTransform>) {
      return y.matrix().squaredNorm();
    } else {
      const double norm = transform_.norm(y);
      return norm * norm;
    }
  }

  // x = inverse(y) and y = forward(x) of the stage path; with a fixed D, fixed-size copies.
  template <class Y>
  void to_physical(const Y& y, Eigen::VectorXd& x) {
    if constexpr (kFixed)
      Eigen::Map<Array>(x.data()) = y;
    else
      transform_.inverse(y, x);
  }
  // With a fixed D, x (the callback's g) is read entry by entry into registers: the callback
  // writes it with scalar stores, and one vector load spanning two of them is not forwarded from
  // the store buffer but waits until they retire. (The empty asm keeps GCC from merging the
  // loads again.) P3 (d = 2), a stand-alone driver, old and new alternated: ~93 -> ~71 ns per
  // stage.
  template <class Y>
  void to_eigen(const Eigen::VectorXd& x, Y&& y) {
    if constexpr (kFixed) {
      Array v;
      for (int k = 0; k < D; ++k) {
        double entry = x[k];
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
        asm("" : "+x"(entry));
#endif
        v[k] = entry;
      }
      y = v;
    } else
      transform_.forward(x, y);
  }

  // A coefficient of k_ as the arrays see it: a number, or an array map (of fixed size when D
  // is, so that expressions mixing it with the stage arrays keep the fixed size).
  template <class V>
  static auto co(const V& value) {
    if constexpr (kFixed && !std::is_same_v<V, double>)
      return Eigen::Map<const Eigen::Array<double, D, 1>>(value.data());
    else
      return value;
  }

  // Eq. (d): the stages one by one, then the update, added to the state only at the end.
  void implicit_step(Statistics& stats) {
    const StepCoefficients<Coef>& k = *k_;
    for (int i = 0; i < s_; ++i) {
      start_stage(i);
      if (!fixed_point(i, stats)) {
        ++stats.newton_fallbacks;
        const long before = stats.gradient_evaluations;
        if (d_ <= kDenseNewtonMaxD)
          newton(i, stats);
        else
          newton_krylov(i, stats);
        newton_cost_[i] = double(stats.gradient_evaluations - before);
      }
      if (--adapt_wait_[i] <= 0) adapt_order(i);
    }
    SpectralMap &dq = qw_hat_, &dp = pw_hat_;
    dq = co(k.phi0m1()) * q_hat_ + co(k.hphi1()) * p_hat_;
    dp = co(k.mhMphi1()) * q_hat_ + co(k.phi0m1()) * p_hat_;
    for (int i = 0; i < s_; ++i) {
      dq -= co(k.h2bbar(i)) * G(i);
      dp -= co(k.hb(i)) * G(i);
    }
    require_finite_result(q_hat_ + dq, p_hat_ + dp, place());
    add(q_hat_, eq_hat_, dq);
    add(p_hat_, ep_hat_, dp);
  }

  StepPlace place() const { return {&method_, step_number_, t_}; }

  // r_i = phi0(c_i^2 V) q + h c_i phi1(c_i^2 V) p - h^2 sum_{j<i} abar_ij g_j, and the starting
  // guess Q = r_i - h^2 abar_ii g_pred with g_pred extrapolated from the known stage gradients.
  void start_stage(int i) {
    const StepCoefficients<Coef>& k = *k_;
    r_hat_ = co(k.phi0c(i)) * q_hat_ + co(k.hcphi1c(i)) * p_hat_;
    for (int j = 0; j < i; ++j) r_hat_ -= co(k.abar(i, j)) * G(j);
    const int n = std::min(order_[i], available_nodes(i));
    if (n > 0)
      predict(i, n, guess_hat_);
    else
      guess_hat_.setZero();
    Q_hat_ = r_hat_ - co(k.abar(i, i)) * guess_hat_;
    to_physical(Q_hat_, Q_);
  }

  // Stage i's nodes, most recent first: this step's stages j < i (at c_j), then those of the
  // previous steps (at c_j - age); a node at the time of a more recent one is left out.
  void set_nodes(int i) {
    const double* c = method_.table().c;
    const auto time = [&](const Node& node) { return c[node.stage] - node.age; };
    int& n = node_count_[i];
    for (int age = 0; age <= kHistory; ++age)
      for (int j = (age == 0 ? i : s_) - 1; j >= 0; --j) {
        const Node node{age, j};
        bool repeated = false;
        for (int l = 0; l < n; ++l) repeated |= time(nodes_[i][l]) == time(node);
        if (!repeated && n < kMaxNodes) nodes_[i][n++] = node;
      }
    // Lagrange weights at c_i on the first m nodes, for every m.
    for (int m = 1; m <= n; ++m)
      for (int l = 0; l < m; ++l) {
        double w = 1;
        for (int k = 0; k < m; ++k)
          if (k != l) w *= (c[i] - time(nodes_[i][k])) / (time(nodes_[i][l]) - time(nodes_[i][k]));
        weight(i, m - 1, l) = w;
      }
    order_[i] = n;
  }

  // Nodes of stage i whose gradients are known (the steps since set_state).
  int available_nodes(int i) const {
    if (history_ == kHistory) return node_count_[i];  // (every node: the usual case)
    int n = 0;
    while (n < node_count_[i] && nodes_[i][n].age <= history_) ++n;
    return n;
  }

  // out = the polynomial through the first n nodes of stage i, at c_i.
  void predict(int i, int n, SpectralMap& out) {
    const auto gradient_at = [&](const Node& node) {
      return SpectralMap(steps_[node.age] + node.stage * stride_, m_);
    };
    out = weight(i, n - 1, 0) * gradient_at(nodes_[i][0]);
    for (int l = 1; l < n; ++l) out += weight(i, n - 1, l) * gradient_at(nodes_[i][l]);
  }

  // Moves stage i's order n to whichever of n - 1, n, n + 1 nodes would have given the solved
  // stage the best guess, |h^2 abar_ii(V) (g_pred - g_i)|: high degrees where the stage gradients
  // are smooth on the scale of h, low ones where they oscillate (the extrapolation then amplifies
  // more than it predicts, most harmfully in the modes with large abar_ii).
  // Checked every step while the order moves; each check that keeps it doubles the interval to
  // the next, up to kMaxAdaptInterval steps: checked at every step, its two more predictions and
  // norms per stage cost P2/P3 15-20% of the CPU per grad U (erkn_implicit_benchmark) and saved
  // no evaluation there; with the interval, evaluations per stage (erkn_stage_evaluations) moved
  // by <= 0.05 on P1-P3, and P1's savings (SERKN3s4(1) at 1e-9: 1.13 against 1.42) stay.
  void adapt_order(int i) {
    const int available = available_nodes(i), n = std::min(order_[i], available);
    if (available < 2) return;  // (adapt_wait_ <= 0: checked at the next step)
    const auto guess_error = [&](SpectralMap& prediction) {  // (squared: only compared)
      prediction = co(k_->abar(i, i)) * (prediction - G(i));
      return squared_norm(prediction);
    };
    double best = guess_error(guess_hat_);  // (start_stage's prediction, n nodes)
    int best_n = n;
    for (int m : {n - 1, n + 1}) {
      if (m < 1 || m > available) continue;
      predict(i, m, Q_hat_new_);  // (free between stages)
      const double error = guess_error(Q_hat_new_);
      if (error < best) best = error, best_n = m;
    }
    adapt_interval_[i] =
        best_n == order_[i] ? std::min(2 * adapt_interval_[i], kMaxAdaptInterval) : 1;
    adapt_wait_[i] = adapt_interval_[i];
    order_[i] = best_n;
  }

  // Fixed point Q <- r_i - h^2 abar_ii(V) g(Q). True when converged, or when the updates stall
  // below Options::roundoff_level (a tolerance under the round-off noise); G(i) then holds the
  // gradient of the last iterate but one (no confirming evaluation).
  // The tests on theta = delta / delta_old are multiplied out (theta/(1-theta) delta <= tol as
  // delta^2 <= tol (delta_old - delta)), and the too-slow test needs no logarithm (too_slow).
  bool fixed_point(int i, Statistics& stats) {
    double delta = 0, delta_old = 0, norm2_Q = 0, change_first = 0;
    int extra = 0;  // iterations after convergence from a cold start (reset_tightening)
    const auto abar_ii = co(k_->abar(i, i));
    for (int it = 1; it <= options_.max_fixed_point_iterations; ++it) {
      if (it > 1) to_physical(Q_hat_, Q_);  // (start_stage did it for the guess)
      force(Q_, i, stats);
      to_eigen(g_, G(i));
      Q_hat_new_ = r_hat_ - abar_ii * G(i);
      ++stats.stage_iterations;
      // |dQ| / max(|Q_new|, |Q_old|) in eigen coordinates, so a converged stage needs no inverse
      // transform. Both iterates: an iterate at 0 (a 2-cycle r -> 0 -> r) must not make delta
      // huge and the next theta ~ 0, which would pass the stopping test without converging.
      const double change2 = squared_norm(Q_hat_new_ - Q_hat_);
      if (it == 1) norm2_Q = squared_norm(Q_hat_);  // later: the previous iterate's norm2_new
      const double norm2_new = squared_norm(Q_hat_new_);
      delta = relative_change(change2, std::max(norm2_new, norm2_Q));
      norm2_Q = norm2_new;
      swap_views(Q_hat_, Q_hat_new_);
      if (it == 2 && change_first > 0) record_contraction(i, change_first, delta, delta_old);
      // A first update below round-off (delta = 0) proves nothing: the guess then holds the
      // extrapolation's error below round-off, and stopping there let RKN3s4(2) drift in energy
      // over 1e6 steps of P3 (h = 1e-3).
      if (delta == 0 && it > 1) return true;
      if (it == 1 && delta > 0 && contraction_proves(i, delta)) return true;
      if (it == 1) change_first = std::sqrt(change2), g_first_hat_ = G(i);
      if (it > 1) {
        if (delta < delta_old && delta * delta <= options_.tolerance * (delta_old - delta)) {
          if (!reset_tightening(delta, delta_old, extra)) return true;
          delta_old = delta;  // (converged: the next iteration only tightens, and cannot fail)
          continue;
        }
        if (extra > 0) return true;  // (converged before; this iteration did not contract)
        if (delta >= options_.max_theta * delta_old)
          return delta <= options_.roundoff_level;  // stagnation at round-off, else diverging
        if (too_slow(i, it, delta, delta_old) && delta > options_.roundoff_level) return false;
      }
      delta_old = delta;
    }
    // Out of iterations: accept only round-off noise, or a converged stage's extra iterations.
    return extra > 0 || delta <= options_.roundoff_level;
  }

  // After a reset of the starting-guess history (construction, set_state, a shorter step, a
  // monitor rollback) the guess is poor, and theta/(1-theta) |dQ| can pass the tolerance while
  // the stage is still off by ~1e-11 (FPU, omega = 50, h omega = 1: SERKN3s4(1) 1.0e-11 relative
  // after one step, SERKN4s6 6.7e-12, against stages iterated to round-off). There the fixed
  // point iterates on after converging, up to kResetExtra times, until the estimate is within
  // kResetShare of the tolerance. Its stopping test stays the tolerance: a tighter one made
  // steps at half the predicted fixed-point limit fall back to Newton (ff85219, reverted).
  // True when one more iteration is due; counts it in `extra`. (The estimate theta/(1-theta)
  // delta with theta = delta / delta_old is delta^2 / (delta_old - delta).)
  static constexpr double kResetShare = 0.01;
  static constexpr int kResetExtra = 4;
  bool reset_tightening(double delta, double delta_old, int& extra) const {
    if (history_ > 0 || extra >= kResetExtra ||
        delta * delta / (delta_old - delta) <= kResetShare * options_.tolerance)
      return false;
    ++extra;
    return true;
  }

  // sqrt(change2 / norm2), norm2 the larger squared norm of the two iterates (floored: an
  // iterate of norm below 1e-300 counts as 1e-300).
  static double relative_change(double change2, double norm2) {
    if (change2 == 0) return 0;
    if (norm2 >= std::numeric_limits<double>::min()) return std::sqrt(change2 / norm2);
    return std::sqrt(change2) / std::max(std::sqrt(norm2), 1e-300);
  }

  // Whether reaching the tolerance at theta = delta / delta_old (< max_theta) would take more
  // iterations than are left, or more than Newton's last solve of this stage cost: K more
  // iterations leave theta^(K+1)/(1-theta) delta.
  bool too_slow(int i, int it, double delta, double delta_old) const {
    const double theta = delta / delta_old;
    int left = options_.max_fixed_point_iterations - it;
    if (newton_cost_[i] > 0) left = std::min(left, int(newton_cost_[i]));
    double power = theta;  // theta^(left + 1) by squaring
    for (double base = theta; left > 0; left >>= 1, base *= base)
      if (left & 1) power *= base;
    return power * delta > options_.tolerance * (1 - theta);
  }

  // The contraction theta of stage i's iteration is a property of h, M and U near the solution:
  // measured at a second iteration (record_contraction), it lets a later first iteration stop
  // once theta/(1-theta) |dQ| weight_i <= kFirstShare * tolerance with theta = kThetaSafety times
  // the measurement (no second evaluation to measure it again). Measured afresh at every second
  // iteration, and forced by one every kThetaRefresh solves of that stage. The step then uses
  // g(Q_0), whose error reaches (q, p) through bbar_i and b_i rather than abar_ii: weight_i =
  // max(1, |bbar_i| / |abar_ii|, |b_i| / (h |abar_ii|)). kFirstShare: that error is the
  // extrapolation's, systematic, so it adds up over the steps (a converged second iteration leaves
  // round-off): at the full tolerance P1's error at 1e-9 changed by up to 25% against stages
  // iterated to round-off (erkn_stage_evaluations, "vs tol 0"), at a hundredth of it by < 2e-11.
  static constexpr double kThetaSafety = 4, kFirstShare = 0.01;
  // Newton with a dense LU up to this d, Newton-Krylov (GMRES) beyond it.
  static constexpr Eigen::Index kDenseNewtonMaxD = 256;
  static constexpr int kKrylovRestart = 30, kKrylovMaxIterations = 200;
  // GMRES's relative tolerance: kKrylovTolerance, loosened up to kMaxForcing where the linear
  // residual may stay at kLinearShare * tolerance * |Q| (no solve below what the stage needs: a
  // Newton iteration that only confirms convergence then costs 1-2 products instead of 5-12).
  static constexpr double kKrylovTolerance = 1e-6, kMaxForcing = 0.1, kLinearShare = 0.1;
  // Newton stops with an error after this many successive iterations that did not contract.
  static constexpr int kMaxStalls = 2;
  // Newton-Krylov starts from the failed fixed point's iterate within this relative distance of
  // the starting guess (SERKN3s4(1), sine-Gordon N = 2048, 24 steps: 10.9 -> 7.9 grad U per
  // fallback).
  static constexpr double kKeepIterate = 1e-3;
  static constexpr int kThetaRefresh = 8;
  static constexpr double kEps = std::numeric_limits<double>::epsilon();

  // theta/(1-theta) delta weight_i <= kFirstShare * tolerance, as delta <= first_limit_[i].
  bool contraction_proves(int i, double delta) {
    if (theta_[i] < 0 || ++theta_age_[i] >= kThetaRefresh) return false;
    return delta <= first_limit_[i];
  }

  // theta along the first update, |h^2 abar_ii (g(Q_1) - g(Q_0))| / |Q_1 - Q_0|, with g(Q_0) in
  // g_first_hat_ and g(Q_1) in G(i). Not the ratio of the updates |Q_2 - Q_1| / |Q_1 - Q_0|: Q_2 =
  // r_i - h^2 abar_ii g(Q_1) cancels against r_i, so once the guess is good that ratio measures
  // the round-off of Q, not theta (P3, SERKN3s4(1), h = 1/4: |Q_1 - Q_0| ~ 1e-11 |Q|, the ratio
  // 1e-5..1e-4 against theta ~ 1e-6), and the first-iteration stop seldom passed. Below ~1e3
  // round-offs the first update is not measured: the old measurement is only renewed when the
  // ratio does not exceed what it allowed. First-iteration stops on guesses that good keep their
  // error systematic over millions of steps (RKN3s4(2) on P3 at h = 1e-3, 1e6 steps: the energy
  // error grew 10-fold, 1.4e-12 -> 1.4e-11, when they were allowed; energy_test).
  void record_contraction(int i, double change_first, double delta, double delta_first) {
    if (delta_first < 1e3 * kEps) {
      const double ratio = (delta == 0 ? kEps : delta) / delta_first;
      if (theta_[i] >= 0 && ratio <= kThetaSafety * theta_[i]) theta_age_[i] = 0;
      return;
    }
    g_first_hat_ = co(k_->abar(i, i)) * (G(i) - g_first_hat_);
    theta_[i] = std::sqrt(squared_norm(g_first_hat_)) / change_first;
    theta_age_[i] = 0;
    const double theta = kThetaSafety * theta_[i];
    first_limit_[i] = !(theta < 0.5) ? -1.0
                      : theta > 0
                          ? kFirstShare * options_.tolerance * (1 - theta) / (theta * weight_[i])
                          : std::numeric_limits<double>::max();
  }

  // Newton on F(Q) = Q - r_i + h^2 abar_ii(V) g(Q) from the starting guess, Jacobian
  // I + h^2 abar_ii(V) (Hessian [+ M for RKN]).
  void newton(int i, Statistics& stats) {
    if (J_.rows() != d_) {
      J_.resize(d_, d_);
      H_.resize(d_, d_);
      for (Eigen::VectorXd* x : {&r_, &F_, &gU_, &col_, &Q_new_}) x->resize(d_);
      col_hat_.resize(Q_hat_.size());
      lu_ = Eigen::PartialPivLU<Eigen::MatrixXd>(d_);
      if (rkn_) M_dense_ = system_.M.to_dense(d_);
    }
    transform_.inverse(r_hat_, r_);
    Q_hat_ = r_hat_ - k_->abar(i, i) * guess_hat_;
    transform_.inverse(Q_hat_, Q_);
    double delta_old = 0, residual = 0;
    int it = 1, stalls = 0;
    for (; it <= options_.max_newton_iterations; ++it) {
      gradient(Q_, gU_, i, stats);
      g_ = gU_;
      add_MQ(Q_);
      transform_.forward(g_, G(i));
      Q_hat_ = k_->abar(i, i) * G(i);
      transform_.inverse(Q_hat_, F_);
      F_ += Q_ - r_;
      residual = F_.norm() / std::max(Q_.norm(), 1e-300);
      jacobian(i, stats);
      lu_.compute(J_);
      Q_new_ = lu_.solve(F_);
      Q_ -= Q_new_;
      ++stats.newton_iterations, ++stats.stage_iterations;
      const double delta = Q_new_.norm() / std::max(Q_.norm(), 1e-300);
      if (!std::isfinite(delta)) break;  // the Jacobian is singular
      if (newton_converged(delta, delta_old, it)) {
        // h^2 abar_ii |Hessian| may be large here, so G(i) must be the gradient at the final Q.
        force(Q_, i, stats);
        transform_.forward(g_, G(i));
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
  bool newton_converged(double delta, double delta_old, int it) const {
    const double theta = it > 1 ? delta / delta_old : 1;
    return delta == 0 || (theta < 1 && theta / (1 - theta) * delta <= options_.tolerance) ||
           (it > 1 && theta >= 1 && delta <= options_.roundoff_level);
  }

  // Fails fast (instead of running out of iterations) once kMaxStalls successive iterations
  // changed Q by at least as much as the one before them, above Options::roundoff_level: such an
  // iteration sits at its own noise floor (round-off of F, directional differences) or diverges.
  void check_contraction(int i, const char* solver, double delta, double delta_old, int it,
                         int& stalls, double residual) const {
    stalls = it > 1 && delta >= delta_old ? stalls + 1 : 0;
    if (stalls < kMaxStalls) return;
    not_converged(i, residual, it,
                  std::string(": ") + solver + " stopped contracting (relative change " +
                      format(delta, 3) + " in the last of " + std::to_string(kMaxStalls) +
                      " iterations without contraction, above Options::roundoff_level = " +
                      format(options_.roundoff_level, 3) + ")");
  }

  [[noreturn]] void not_converged(int i, double residual, int iterations,
                                  const std::string& why = "") const {
    throw Error(
        "step " + std::to_string(step_number_) + " at t = " + format(t_) + ": stage " +
        std::to_string(i + 1) + " of " + std::string(method_.name()) +
        " did not converge (fixed-point iteration failed; Newton left a relative residual " +
        format(residual, 3) + " after " +
        std::to_string(std::min(iterations, options_.max_newton_iterations)) + " iterations" + why +
        "); the state is unchanged");
  }

  // Newton-Krylov's storage (on first use), r_ and its first iterate Q_: the fixed point's last
  // iterate (Q_hat_) when it stayed within kKeepIterate of the starting guess (it failed on a
  // few slow modes near poles of abar_ii after reducing the others' error), else the guess (it
  // diverged).
  void start_newton_krylov(int i) {
    if (!gmres_) {
      for (Eigen::VectorXd* x : {&r_, &F_, &gU_, &col_, &Q_new_, &Qe_, &ge_}) x->resize(d_);
      col_hat_.resize(Q_hat_.size());
      gmres_.emplace(d_, kKrylovRestart);
    }
    transform_.inverse(r_hat_, r_);
    const double guess2 = squared_norm(r_hat_ - k_->abar(i, i) * guess_hat_);
    if (!(squared_norm(Q_hat_ - (r_hat_ - k_->abar(i, i) * guess_hat_)) <=
          kKeepIterate * kKeepIterate * guess2))
      Q_hat_ = r_hat_ - k_->abar(i, i) * guess_hat_;
    transform_.inverse(Q_hat_, Q_);
  }

  // Newton on the same F for d > kDenseNewtonMaxD without any d x d matrix: each linear system
  // J dQ = F is solved by (flexible) GMRES with J v = v + h^2 abar_ii(V) K v, K v a directional
  // difference of grad U (+ M v), right-preconditioned in M's eigenbasis by
  // 1 + h^2 abar_ii(v_k) sigma, sigma = w^T K w / w^T w the Hessian's Rayleigh quotient along the
  // first residual w (measured by GMRES's first product, which is left unpreconditioned).
  void newton_krylov(int i, Statistics& stats) {
    start_newton_krylov(i);
    double delta_old = 0, residual = 0;
    int it = 1, stalls = 0;
    bool sigma_pending = true;
    const auto apply = [&](const auto& v, Eigen::VectorXd& Jv) {
      jacobian_times(i, v, Jv, stats);
      if (!sigma_pending) return;
      set_preconditioner(i, v.dot(ge_) / v.squaredNorm());  // (v != 0: GMRES's first vector)
      sigma_pending = false;
    };
    const auto precondition = [&](const auto& v, auto&& z) {
      if (sigma_pending) {
        z = v;
        return;
      }
      col_ = v;
      transform_.forward(col_, col_hat_);
      col_hat_ /= precond_;
      transform_.inverse(col_hat_, col_);
      z = col_;
    };
    for (; it <= options_.max_newton_iterations; ++it) {
      force(Q_, i, stats);
      gU_ = g_;
      apply_abar(i, g_, F_);
      F_ += Q_ - r_;
      residual = F_.norm() / std::max(Q_.norm(), 1e-300);
      const double forcing =
          std::clamp(kLinearShare * options_.tolerance / residual, kKrylovTolerance, kMaxForcing);
      gmres_->solve(apply, precondition, F_, Q_new_, forcing, kKrylovMaxIterations);
      Q_ -= Q_new_;
      ++stats.newton_iterations, ++stats.stage_iterations;
      const double delta = Q_new_.norm() / std::max(Q_.norm(), 1e-300);
      if (!std::isfinite(delta)) break;
      // |Q_before - Q*| <= delta / (1 - theta): the iterate before this update may already be
      // within the tolerance, and its gradient is known (no confirming evaluation).
      if (it > 1 && delta < delta_old && delta / (1 - delta / delta_old) <= options_.tolerance) {
        Q_ += Q_new_;
        transform_.forward(gU_, G(i));
        return;
      }
      if (newton_converged(delta, delta_old, it)) {
        force(Q_, i, stats);
        transform_.forward(g_, G(i));
        return;
      }
      check_contraction(i, "Newton-Krylov", delta, delta_old, it, stalls, residual);
      delta_old = delta;
    }
    not_converged(i, residual, it);
  }

  // out = h^2 abar_ii(V) x, through the eigenbasis.
  void apply_abar(int i, const Eigen::VectorXd& x, Eigen::VectorXd& out) {
    transform_.forward(x, col_hat_);
    col_hat_ *= k_->abar(i, i);
    transform_.inverse(col_hat_, out);
  }

  // Jv = v + h^2 abar_ii(V) (g(Q + e v) - g(Q)) / e, with g_ = grad U (+ M Q) at Q_ in gU_.
  template <class V>
  void jacobian_times(int i, const V& v, Eigen::VectorXd& Jv, Statistics& stats) {
    const double norm_v = v.norm();
    if (norm_v == 0) {
      Jv.setZero(d_);
      return;
    }
    const double e = std::sqrt(std::numeric_limits<double>::epsilon()) * (1 + Q_.norm()) / norm_v;
    Qe_ = Q_ + e * v;
    force(Qe_, i, stats);
    ge_ = (g_ - gU_) / e;
    apply_abar(i, ge_, Jv);
    Jv += v;
  }

  // precond_ = 1 + h^2 abar_ii(v_k) sigma (entries near 0 replaced by 1: no division by ~0).
  void set_preconditioner(int i, double sigma) {
    precond_ = (Eigen::ArrayXd::Zero(m_) + k_->abar(i, i)) * sigma + 1.0;
    precond_ = (precond_.abs() < 1e-2).select(1.0, precond_);
  }

  // J = I + h^2 abar_ii(V) K with K the Hessian of U (user's or finite differences) [+ M].
  void jacobian(int i, Statistics& stats) {
    if (system_.hessian) {
      system_.hessian(Q_, H_);
      ++stats.hessian_evaluations;
      if (H_.rows() != d_ || H_.cols() != d_ || !H_.allFinite())
        throw Error("the Hessian callback returned a non-finite value or a size other than " +
                    std::to_string(d_) + "x" + std::to_string(d_) + " at step " +
                    std::to_string(step_number_));
    } else {
      for (Eigen::Index j = 0; j < d_; ++j) {
        const double saved = Q_[j], step = 1e-7 * std::max(1.0, std::abs(saved));
        Q_[j] = saved + step;
        gradient(Q_, col_, i, stats);
        Q_[j] = saved;
        H_.col(j) = (col_ - gU_) / step;
      }
    }
    if (rkn_) H_ += M_dense_;
    for (Eigen::Index j = 0; j < d_; ++j) {
      col_ = H_.col(j);
      transform_.forward(col_, col_hat_);
      col_hat_ *= k_->abar(i, i);
      transform_.inverse(col_hat_, col_);
      J_.col(j) = col_;
    }
    J_.diagonal().array() += 1.0;
  }

  // g_ = grad U(Q) (+ M Q for RKN methods).
  void force(const Eigen::VectorXd& Q, int i, Statistics& stats) {
    gradient(Q, g_, i, stats);
    add_MQ(Q);
  }

  // g_ += M Q. With a fixed D and a scalar or diagonal M inline, g_k += m_k Q_k: the products
  // MOperator::apply forms, without its call and the pass over Mq_ (P2, D = 1: 15-18 % less CPU
  // per evaluation for RKN1s2(1), RKN2s4, RKN3s4(1); a driver stepping the Stepper alone).
  void add_MQ(const Eigen::VectorXd& Q) {
    if (!rkn_) return;
    if constexpr (kFixed) {
      if (m_diagonal_) {
        Eigen::Map<Array>(g_.data()) += m_diag_ * Eigen::Map<const Array>(Q.data());
        return;
      }
    }
    M_.apply(Q, Mq_);
    g_ += Mq_;
  }

  // m_diag_ for add_MQ: M's diagonal when it is scalar or diagonal (fixed D only).
  void set_m_diagonal() {
    using S = Stiffness::Structure;
    const Stiffness& M = system_.M;
    if constexpr (kFixed) {
      if (M.structure() == S::scalar) m_diag_.setConstant(M.entries()[0]);
      if (M.structure() == S::diagonal) m_diag_ = M.entries().array();
      m_diagonal_ = M.structure() == S::scalar || M.structure() == S::diagonal;
    }
  }

  void gradient(const Eigen::VectorXd& Q, Eigen::VectorXd& g, int i, Statistics& stats) {
    checked_gradient<D>(system_, Q, g, d_, i, place(), stats.gradient_evaluations);
  }

  // x += dx in eigen coordinates, Kahan-compensated when enabled (compensated_sum.hpp).
  void add(SpectralMap& x, SpectralMap& error, SpectralMap& dx) {
    if (options_.compensated_summation)
      compensated_add(x, error, dx);
    else
      x += dx;
  }

  // max_k |num_k| / |den_k| over the eigen coordinates (numbers or arrays; no allocation).
  template <class A, class B>
  static double max_ratio(const A& num, const B& den) {
    if constexpr (std::is_same_v<B, double>)
      return std::abs(num) / std::abs(den);
    else
      return (num.abs() / den.abs()).maxCoeff();
  }

  template <size_t n, class T>
  static std::array<T, n> filled(T x) {
    std::array<T, n> a;
    a.fill(x);
    return a;
  }

  Scalar* slot(int k) { return spectral_.data() + k * stride_; }
  SpectralMap G(int i) { return {steps_[0] + i * stride_, m_}; }

  // Exchanges the arrays two maps view (Map::swap would exchange their contents).
  static void swap_views(SpectralMap& a, SpectralMap& b) {
    Scalar* const data = a.data();
    new (&a) SpectralMap(b.data(), b.size());
    new (&b) SpectralMap(data, a.size());
  }

  Method method_;
  System system_;
  Options options_;
  bool rkn_;
  Eigen::Index d_;
  int s_;
  std::optional<StepCoefficients<Coef>> k_;
  Transform transform_;
  MOperator M_;
  long step_number_ = 0;  // of the step being taken, and its t, for messages
  double t_ = 0;
  // Starting values: stage i's gradient extrapolated through its order_[i] most recent known
  // stage gradients (nodes_[i], their Lagrange weights at c_i in weight(i, order - 1, .)), from
  // this step and the kHistory before it.
  static constexpr int kMaxNodes = (kHistory + 1) * kMaxStages;
  struct Node {
    int age, stage;  // age 0: this step
  };
  std::array<std::array<Node, kMaxNodes>, kMaxStages> nodes_{};
  std::array<int, kMaxStages> node_count_{}, order_{};
  // weight(i, m - 1, l): node l's Lagrange weight at c_i on the first m nodes; sized by s, not
  // by kMaxStages (that would be kMaxStages (2 kMaxStages)^2 doubles to clear at every setup).
  std::vector<double> weights_;
  double& weight(int i, int m, int l) {
    const int n = (kHistory + 1) * s_;
    return weights_[(size_t(i) * n + m) * n + l];
  }
  int history_ = 0;  // steps before this one with stage gradients (since set_state)
  static constexpr int kMaxAdaptInterval = 8;
  std::array<int, kMaxStages> adapt_wait_ = filled<kMaxStages>(1);  // steps to adapt_order's check
  std::array<int, kMaxStages> adapt_interval_ = filled<kMaxStages>(1);
  std::array<double, kMaxStages> theta_ = filled<kMaxStages>(-1.0);  // measured; < 0: none
  std::array<int, kMaxStages> theta_age_{};       // stage solves since the measurement
  std::array<double, kMaxStages> first_limit_{};  // the largest delta a first iteration may stop at
  std::array<double, kMaxStages> weight_{};
  std::array<double, kMaxStages> newton_cost_{};  // evaluations of its last Newton solve; 0: none
  // The arrays in eigen coordinates, m_ entries each and stride_ apart in spectral_ (one
  // allocation): the state (q, p) and its summation errors, the increments dq, dp of a step,
  // five stage arrays, then the s stage gradients of this step and of the kHistory before it
  // (steps_[age]).
  Eigen::Index m_, stride_;
  alignas(EIGEN_MAX_ALIGN_BYTES) Storage spectral_;
  SpectralMap q_hat_, p_hat_, eq_hat_, ep_hat_, qw_hat_, pw_hat_;
  SpectralMap r_hat_, Q_hat_, Q_hat_new_, guess_hat_, g_first_hat_;
  std::array<Scalar*, kHistory + 1> steps_{};
  Eigen::VectorXd Q_, g_, Mq_;  // (Q_, g_ go to the callbacks)
  bool m_diagonal_ = false;     // RKN, fixed D, M scalar or diagonal: M = diag(m_diag_)
  Eigen::Array<double, kFixed ? D : 1, 1> m_diag_;
  // Newton workspace, allocated at the first fallback.
  Eigen::MatrixXd J_, H_, M_dense_;
  Eigen::VectorXd r_, F_, gU_, col_, Q_new_;
  Spectral col_hat_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  // Newton-Krylov workspace (d > kDenseNewtonMaxD), allocated at the first fallback.
  Eigen::VectorXd Qe_, ge_;
  Eigen::ArrayXd precond_;
  std::optional<Gmres> gmres_;
};

}  // namespace erkn::detail
