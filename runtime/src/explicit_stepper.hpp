// The step of an explicit method (every abar_ii identically 0), generic over M's eigenbasis
// (Transform) and the coefficient type (Coef). Such a method is a splitting (DESIGN.md section 1,
// the explicit family) and steps as one: exact flows of q'' + M q = 0 over tau_k =
// h (c_k - c_{k-1}) (c_0 = 0 before the first node, c_{s+1} = 1 after the last) alternated with
// kicks p -= h d_k g_k, g_k = grad U(Q_k) (+ M Q_k for RKN methods), each one pass over the
// eigen coordinates (Kahan-compensated when enabled). The first pass reads the state and every
// pass writes a second copy of it, which replaces the state once every gradient has been
// evaluated: a failed step leaves the state unchanged. With c_1 = 0 and c_s = 1 the first kick
// reuses the previous step's last gradient (FSAL). D: the dimension when it is a compile-time
// constant (tiny systems with M's identity eigenbasis: every pass then unrolls).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <type_traits>
#include <utility>

#include "erkn/integrator.hpp"
#include "m_operator.hpp"
#include "stage_checks.hpp"
#include "step_coefficients.hpp"
#include "stepper_base.hpp"

namespace erkn::detail {

template <class Transform, class Coef, int D = Eigen::Dynamic>
class ExplicitStepper final : public StepperBase {
  using Spectral = typename Transform::Spectral;
  using Scalar = typename Spectral::Scalar;
  // (Aligned when stride_ keeps the arrays aligned: in the dynamic-size storage.)
  using SpectralMap =
      Eigen::Map<Spectral, D == Eigen::Dynamic ? Eigen::AlignedMax : Eigen::Unaligned>;
  static constexpr bool kIdentity = std::is_same_v<Transform, IdentityTransform>;
  static_assert(D == Eigen::Dynamic || kIdentity, "a fixed dimension needs the identity basis");
  // The state and its copy (4 arrays each), the gradient of the current stage and the last
  // stage's gradient of the previous step.
  static constexpr int kArrays = 10;
  // Their storage: one allocation, or (fixed dimension) inside the stepper.
  using Storage = std::conditional_t<D == Eigen::Dynamic, Spectral,
                                     std::array<Scalar, kArrays * std::max(D, 1)>>;

  /// One copy of the state in eigen coordinates: q, p and their summation errors.
  struct State {
    Scalar *q, *p, *eq, *ep;
  };

 public:
  /// lambda: M's eigenvalue of each eigen coordinate ({0} for RKN methods, whose force then
  /// includes M q).
  ExplicitStepper(const Method& method, System system, double h, const Options& options,
                  Transform transform, const Eigen::VectorXd& lambda, Eigen::Index d)
      : method_(method),
        system_(std::move(system)),
        kahan_(options.compensated_summation),
        rkn_(method.kind() == Kind::rkn),
        s_(method.stages()),
        fsal_(s_ > 1 && method.table().c[0] == 0 && method.table().c[s_ - 1] == 1),
        d_(d),
        flows_(method, h, lambda),
        transform_(std::move(transform)),
        M_(system_.M, d),
        m_(transform_.spectral_size(d)),
        stride_(D == Eigen::Dynamic ? aligned_stride<Scalar>(m_) : D),
        spectral_(zeros(stride_)),
        state_{slot(0), slot(1), slot(2), slot(3)},
        work_{slot(4), slot(5), slot(6), slot(7)},
        G_(slot(8)),
        G_last_(slot(9)),
        Q_(Eigen::VectorXd::Zero(d)),
        g_(Eigen::VectorXd::Zero(d)) {
    for (int i = 0; i < s_; ++i) hd_[i] = h * method.table().d[i];
    if (rkn_) Mq_.setZero(d);
  }

  ExplicitStepper(const ExplicitStepper&) = delete;  // (the pointers view its own buffer)
  ExplicitStepper& operator=(const ExplicitStepper&) = delete;

  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p) override {
    transform_.forward(q, map(state_.q));
    transform_.forward(p, map(state_.p));
    map(state_.eq).setZero();
    map(state_.ep).setZero();
    have_history_ = false;
  }

  void get_state(Eigen::VectorXd& q, Eigen::VectorXd& p) override {
    transform_.inverse(map(state_.q), q);
    transform_.inverse(map(state_.p), p);
  }

  void step(long step_number, double t, Statistics& stats) override {
    place_.step = step_number;
    place_.t = t;
    long evaluations = 0;  // (counted into stats once the step has succeeded)
    if (kahan_)
      passes<true>(evaluations);
    else
      passes<false>(evaluations);
    std::swap(state_, work_);
    std::swap(G_, G_last_);  // (FSAL: the last stage's gradient)
    have_history_ = true;
    ++stats.steps;
    stats.gradient_evaluations += evaluations;
    stats.stage_iterations += evaluations;
  }

  void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) override { M_.apply(x, y); }
  System& system() override { return system_; }

 private:
  static Storage zeros(Eigen::Index stride) {
    if constexpr (D == Eigen::Dynamic)
      return Spectral::Zero(kArrays * stride);
    else
      return Storage{};
  }

  // The flows and kicks from state_ into work_ (without summation errors when !kKahan: they
  // then stay zero).
  template <bool kKahan>
  void passes(long& evaluations) {
    State from = state_;
    for (int i = 0; i < s_; ++i) {
      const bool reuse = i == 0 && fsal_ && have_history_;
      // In the identity basis the flow writes the stage's Q_ as it goes and the kick saves the
      // gradient to G_ (for FSAL): no pass reloads what the last one stored.
      double* const Q = kIdentity && !reuse ? Q_.data() : nullptr;
      bool have_Q = false;
      if (flows_.moves(i)) {
        flow<kKahan>(i, from, Q);
        from = work_;
        have_Q = Q != nullptr;
      }
      if (reuse)
        kick<kKahan>(hd_[0], G_last_, from, nullptr);
      else
        kick<kKahan>(hd_[i], evaluate(from.q, have_Q, i, evaluations), from,
                     kIdentity ? G_ : nullptr);
      from = work_;
    }
    if (flows_.moves(s_)) flow<kKahan>(s_, work_, nullptr);
    const bool q_ok = all_finite(work_.q, n());
    if (!q_ok || !all_finite(work_.p, n())) non_finite_result(q_ok, place_);
  }

  // work_ = the exact flow over tau_k of `from` (which may be work_ itself); its q also to Q
  // when given (identity basis only).
  template <bool kKahan>
  void flow(int k, const State& from, double* Q) {
    const auto cm1 = flows_.cm1(k), sinc = flows_.sinc(k), msinc = flows_.msinc(k);
    for (Eigen::Index e = 0; e < n(); ++e) {
      const Scalar q = from.q[e], p = from.p[e];
      const double c = at(cm1, e);
      add<kKahan>(q, from.eq[e], c * q + at(sinc, e) * p, work_.q[e], work_.eq[e]);
      add<kKahan>(p, from.ep[e], at(msinc, e) * q + c * p, work_.p[e], work_.ep[e]);
      if constexpr (kIdentity)
        if (Q) Q[e] = work_.q[e];
    }
  }

  // work_ = `from` with p -= hd g; g also to save when given.
  template <bool kKahan>
  void kick(double hd, const Scalar* g, const State& from, Scalar* save) {
    for (Eigen::Index e = 0; e < n(); ++e) {
      const Scalar ge = g[e];
      add<kKahan>(from.p[e], from.ep[e], -hd * ge, work_.p[e], work_.ep[e]);
      if (save) save[e] = ge;
    }
    if (from.q == work_.q) return;
    std::copy_n(from.q, n(), work_.q);
    if (kKahan) std::copy_n(from.eq, n(), work_.eq);
  }

  // x_out = x + dx, Kahan-compensated when kKahan (error: the low-order bits lost so far).
  template <bool kKahan>
  static void add(Scalar x, Scalar error, Scalar dx, Scalar& x_out, Scalar& error_out) {
    if constexpr (kKahan) {
      const Scalar y = dx + error, t = x + y;
      error_out = (x - t) + y;
      x_out = t;
    } else {
      x_out = x + dx;
    }
  }

  // The force at the stage q (eigen coordinates; already in Q_ when have_Q), evaluated in
  // physical coordinates: in eigen coordinates in G_, or (identity basis) in g_.
  const Scalar* evaluate(Scalar* q, bool have_Q, int i, long& evaluations) {
    if constexpr (kIdentity) {
      if (!have_Q) std::copy_n(q, n(), Q_.data());
    } else {
      transform_.inverse(map(q), Q_);
    }
    checked_gradient<D>(system_, Q_, g_, d_, i, place_, evaluations);
    if (rkn_) {
      M_.apply(Q_, Mq_);
      g_ += Mq_;
    }
    if constexpr (kIdentity) {
      return g_.data();
    } else {
      transform_.forward(g_, map(G_));
      return G_;
    }
  }

  // The number of eigen coordinates (a constant when D is).
  Eigen::Index n() const {
    if constexpr (D == Eigen::Dynamic)
      return m_;
    else
      return D;
  }

  static double at(double value, Eigen::Index) { return value; }
  template <class Map>
  static double at(const Map& values, Eigen::Index e) {
    return values[e];
  }

  Scalar* slot(int k) { return spectral_.data() + k * stride_; }
  SpectralMap map(Scalar* x) const { return {x, m_}; }

  Method method_;
  System system_;
  bool kahan_, rkn_;
  int s_;
  bool fsal_;
  Eigen::Index d_;
  std::array<double, kMaxStages> hd_{};  // h d_i
  FlowCoefficients<Coef> flows_;
  Transform transform_;
  MOperator M_;
  // kArrays arrays in eigen coordinates, m_ entries each and stride_ apart.
  Eigen::Index m_, stride_;
  Storage spectral_;
  State state_, work_;
  Scalar *G_, *G_last_;
  Eigen::VectorXd Q_, g_, Mq_;  // physical coordinates (Q_, g_ go to the callback)
  bool have_history_ = false;
  StepPlace place_{&method_, 0, 0};
};

}  // namespace erkn::detail
