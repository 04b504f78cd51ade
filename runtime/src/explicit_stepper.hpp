// The step of an explicit method (every abar_ii identically 0), generic over M's eigenbasis
// (Transform) and the coefficient type (Coef). Such a method is a splitting (docs/design.md §1,
// the explicit family) and steps as one: exact flows of q'' + M q = 0 over tau_k =
// h (c_k - c_{k-1}) (c_0 = 0 before the first node, c_{s+1} = 1 after the last) alternated with
// kicks p -= h d_k g_k, g_k = grad U(Q_k) (+ M Q_k for RKN methods), each one pass over the
// eigen coordinates. With c_1 = 0 and c_s = 1 the first kick reuses the previous step's last
// gradient (FSAL). The first pass reads the state and writes a second copy of it, which replaces
// the state once every gradient has been evaluated and the result is finite: a failed step leaves
// the state unchanged.
//
// The last flow of a step and the first of the next are one exact flow (over tau_s + tau_0), so the
// stored state stays one flow behind: after a step it is the state before flow s, which is
// pending (pending_). The next step starts with the merged flow; get_state applies the pending
// flow to a copy. Either way the state returned is the one the unmerged steps give, up to
// round-off. When D, the dimension, is a compile-time constant (tiny systems with M's
// identity eigenbasis) that copy is a set of fixed-size arrays the compiler keeps in registers.
//
// Compensated summation (Options::compensated_summation) keeps with q and p the low-order parts
// eq, ep that rounding has dropped (the state is q + eq, p + ep): each pass adds the rounding
// error of its sums q + dq, p + dp to eq, ep (flow_update, kick_update). get_state returns q + eq
// and p + ep.
//
// Its cost (construction + integrate, on vs off alternated in one process per run, medians of
// 3-5 runs, main 183cf83 + the SIMD passes, loaded 2-core machine): sine-Gordon N = 2048 SABA2
// 100 steps 1.07x, N = 512 Strang 40 steps 1.11x (before the SIMD passes 1.12x and 1.06x).
// That is above the 5 % the runtime allows itself for a default, and it stays the default all
// the same: without it the round-off of q_n + dq grows with the number of steps (a random walk,
// ~sqrt(n) eps |q|), which is what the energy and long-time charts show and what the paper's
// claims rest on; Options::compensated_summation = false is the fast path.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <limits>
#include <type_traits>
#include <utility>

#include "erkn/integrator.hpp"
#include "flow_coefficients.hpp"
#include "m_operator.hpp"
#include "stage_checks.hpp"
#include "stepper_base.hpp"

namespace erkn::detail {

template <class Transform, class Coef, int D = Eigen::Dynamic>
class ExplicitStepper final : public StepperBase {
  using Spectral = typename Transform::Spectral;
  using Scalar = typename Spectral::Scalar;
  static constexpr bool kFixed = D != Eigen::Dynamic;
  // (Aligned when stride_ keeps the arrays aligned: in the dynamic-size storage.)
  static constexpr int kAlignment = kFixed ? Eigen::Unaligned : Eigen::AlignedMax;
  using SpectralMap = Eigen::Map<Spectral, kAlignment>;
  using ConstMap = Eigen::Map<const Spectral, kAlignment>;
  static constexpr bool kIdentity = std::is_same_v<Transform, IdentityTransform>;
  static_assert(!kFixed || kIdentity, "a fixed dimension needs the identity basis");
  // The state (q, p, eq, ep), the gradient of the current stage and the last stage's gradient of
  // the previous step; with a dynamic dimension also the state's second copy (4 arrays).
  static constexpr int kArrays = kFixed ? 6 : 10;
  // Their storage: one allocation, or (fixed dimension) inside the stepper.
  using Storage =
      std::conditional_t<kFixed, std::array<Scalar, kArrays * std::max(D, 1)>, Spectral>;

  /// One copy of the state in eigen coordinates: q, p and their summation errors; Values holds
  /// them (fixed dimension).
  struct State {
    Scalar *q, *p, *eq, *ep;
  };
  using Fixed = Eigen::Array<Scalar, std::max(D, 1), 1>;
  using FixedMap = Eigen::Map<Fixed>;
  struct Values {
    Fixed q, p, eq, ep;
  };

 public:
  /// lambda: M's eigenvalue of each eigen coordinate ({0} for RKN methods, whose force then
  /// includes M q).
  ExplicitStepper(const Method& method, System&& system, double h, const Options& options,
                  Transform transform, const Eigen::VectorXd& lambda, Eigen::Index d)
      : method_(method),
        system_(std::move(system)),
        kahan_(options.compensated_summation),
        rkn_(method.kind() == Kind::rkn),
        s_(method.stages()),
        fsal_(s_ > 1 && method.table().c[0] == 0 && method.table().c[s_ - 1] == 1),
        d_(d),
        h_(h),
        flows_(method, h, lambda),
        transform_(std::move(transform)),
        M_(system_.M, d),
        m_(transform_.spectral_size(d)),
        stride_(kFixed ? D : aligned_stride<Scalar>(m_)),
        spectral_(zeros(stride_)),
        state_{slot(0), slot(1), slot(2), slot(3)},
        G_(slot(4)),
        G_last_(slot(5)),
        work_{slot(6), slot(7), slot(8), slot(9)},
        Q_(Eigen::VectorXd::Zero(d)),
        g_(Eigen::VectorXd::Zero(d)) {
    if (rkn_) Mq_.resize(d);
  }

  ExplicitStepper(const ExplicitStepper&) = delete;  // (the pointers view its own buffer)
  ExplicitStepper& operator=(const ExplicitStepper&) = delete;

  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p) override {
    transform_.forward(q, map(state_.q));
    transform_.forward(p, map(state_.p));
    map(state_.eq).setZero();
    map(state_.ep).setZero();
    have_history_ = false;
    pending_ = false;
  }

  void get_state(Eigen::VectorXd& q, Eigen::VectorXd& p) override {
    if (kahan_)
      load<true>(q, p);
    else
      load<false>(q, p);
  }

  void step(long step_number, double t, Statistics& stats) override {
    place_.step = step_number;
    place_.t = t;
    long evaluations = 0;  // (counted into stats once the step has succeeded)
    if (kahan_)
      passes<true>(evaluations);
    else
      passes<false>(evaluations);
    std::swap(G_, G_last_);  // (FSAL: the last stage's gradient)
    have_history_ = true;
    pending_ = flows_.moves(s_);
    ++stats.steps;
    stats.gradient_evaluations += evaluations;
    stats.stage_iterations += evaluations;
  }

  void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) override { M_.apply(x, y); }
  System& system() override { return system_; }

 private:
  static Storage zeros(Eigen::Index stride) {
    if constexpr (kFixed)
      return Storage{};
    else
      return Spectral::Zero(kArrays * stride);
  }

  // One step into the second copy (a fixed dimension: whole arrays, which the compiler keeps
  // in registers), checked, and then the state (without summation errors when !kKahan: they then
  // stay zero).
  template <bool kKahan>
  void passes(long& evaluations) {
    if constexpr (kFixed) {
      Values v{Fixed(state_.q), Fixed(state_.p), Fixed::Zero(), Fixed::Zero()};
      if (kKahan) v.eq = Fixed(state_.eq), v.ep = Fixed(state_.ep);
      stages<kKahan>(v, v, evaluations);
      require_finite(v);
      FixedMap(state_.q) = v.q, FixedMap(state_.p) = v.p;
      if (kKahan) FixedMap(state_.eq) = v.eq, FixedMap(state_.ep) = v.ep;
    } else {
      stages<kKahan>(state_, work_, evaluations);
      require_finite(work_);
      std::swap(state_, work_);
    }
  }

  // The flows and kicks from `start` into `to` (S: State or Values; start may be to), the first
  // flow merged with the pending one, the last left pending.
  template <bool kKahan, class S>
  EIGEN_ALWAYS_INLINE void stages(const S& start, S& to, long& evaluations) {
    const S* from = &start;
    for (int i = 0; i < s_; ++i) {
      const bool reuse = i == 0 && fsal_ && have_history_;
      // In the identity basis the flow writes the stage's Q_ as it goes and the kick saves the
      // gradient to G_ (for FSAL): no pass reloads what the last one stored.
      double* const Q = kIdentity && !reuse ? Q_.data() : nullptr;
      bool have_Q = false;
      const int k = i == 0 && pending_ ? flows_.merged(method_) : i;
      if (flows_.moves(k)) {
        flow<kKahan>(k, *from, to, Q);
        from = &to;
        have_Q = Q != nullptr;
      }
      if (reuse)
        kick<kKahan>(h_ * method_.table().d[0], G_last_, *from, to, nullptr);
      else
        kick<kKahan>(h_ * method_.table().d[i], evaluate(&from->q[0], have_Q, i, evaluations),
                     *from, to, kIdentity ? G_ : nullptr);
      from = &to;
    }
  }

  // get_state: q + eq and p + ep after the pending flow, rounded (with a dynamic dimension: in
  // the second copy's slots, unused between steps).
  template <bool kKahan>
  void load(Eigen::VectorXd& q, Eigen::VectorXd& p) {
    if constexpr (kFixed) {
      Values v{Fixed(state_.q), Fixed(state_.p), Fixed(state_.eq), Fixed(state_.ep)};
      if (pending_) flow<kKahan>(s_, v, v, nullptr);
      q = (v.q + v.eq).matrix(), p = (v.p + v.ep).matrix();
    } else {
      const State* from = &state_;
      if (pending_) flow<kKahan>(s_, state_, work_, nullptr), from = &work_;
      if (kKahan) {
        map(work_.q) = map(from->q) + map(from->eq);
        map(work_.p) = map(from->p) + map(from->ep);
        from = &work_;
      }
      transform_.inverse(map(from->q), q);
      transform_.inverse(map(from->p), p);
    }
  }

  void require_finite(const Values& v) const {
    const double big = std::numeric_limits<double>::max();
    const bool q_ok = (v.q.abs() <= big).all();
    if (!q_ok || !(v.p.abs() <= big).all()) non_finite_result(q_ok, place_);
  }
  template <class S>
  void require_finite(const S& x) const {
    const bool q_ok = all_finite(&x.q[0], n());
    if (!q_ok || !all_finite(&x.p[0], n())) non_finite_result(q_ok, place_);
  }

  // The exact flow of (q, p) with coefficients cos, cos - 1, sin(w tau)/w, -w sin(w tau), for
  // one coordinate (T = double) or a whole fixed-size array; and the kick p += dp.
  //
  // Compensated, each pass adds the rounding error of q + dq (p + dp) to eq (ep), dq =
  // (cos - 1) q + sinc p for the flow. With a fixed dimension, where the step is a chain of
  // dependent operations, the errors are folded into q and p at the kick, from values known
  // before dp (whose gradient comes last). With arrays, where the passes' memory traffic counts,
  // each pass folds them into its own increments (dq + eq, dp + ep) and keeps the residuals of
  // the sums: the flow then reads cos - 1 but not cos, and the kick makes one sum, not two.
  static constexpr bool kFoldAtKick = kFixed;

  template <bool kKahan, class T, class C>
  EIGEN_ALWAYS_INLINE static void flow_update(const C& cos, const C& cm1, const C& sinc,
                                              const C& msinc, T& q, T& p, T& eq, T& ep) {
    const T q0 = q, p0 = p;
    if constexpr (kKahan && !kFoldAtKick) {
      const T dq = (cm1 * q0 + sinc * p0) + eq, dp = (msinc * q0 + cm1 * p0) + ep;
      q = q0 + dq, p = p0 + dp;
      eq = (q0 - q) + dq, ep = (p0 - p) + dp;
    } else {
      const T sp = sinc * p0, mq = msinc * q0;
      p = mq + cos * p0;
      q = cos * q0 + sp;
      if constexpr (kKahan) {
        eq += (q0 - q) + (cm1 * q0 + sp);
        ep += (p0 - p) + (mq + cm1 * p0);
      }
    }
  }

  template <bool kKahan, class T>
  EIGEN_ALWAYS_INLINE static void kick_update(const T& dp, T& q, T& p, T& eq, T& ep) {
    if constexpr (kKahan && kFoldAtKick) {
      const T q1 = q + eq;
      eq = (q - q1) + eq;
      q = q1;
      const T p1 = p + ep, e1 = (p - p1) + ep;
      p = p1 + dp;
      ep = e1 + ((p1 - p) + dp);
    } else if constexpr (kKahan) {
      const T p0 = p, dpe = dp + ep;
      p = p0 + dpe;
      ep = (p0 - p) + dpe;
    } else {
      p += dp;
    }
  }

  // The arrays' passes run over doubles: a complex eigen coordinate (half spectrum) is kLanes = 2
  // of them, re and im, which share their real coefficients. Every array a pass writes is a
  // distinct stream (__restrict; an in-place pass reads through the pointer it writes), so the
  // loops compile to SIMD (checked with -fopt-info-vec).
  static constexpr int kLanes = int(sizeof(Scalar) / sizeof(double));
  static double* lanes(Scalar* x) { return reinterpret_cast<double*>(x); }
  static const double* lanes(const Scalar* x) { return reinterpret_cast<const double*>(x); }

  // Flow k from `from` to `to` (in place when they are the same); its q also to Q when given
  // (identity basis only).
  template <bool kKahan>
  EIGEN_ALWAYS_INLINE void flow(int k, const State& from, State& to, double* Q) {
    if (&from == &to)
      flow_pass<kKahan, true>(k, from, to, Q);
    else
      flow_pass<kKahan, false>(k, from, to, Q);
  }
  template <bool kKahan, bool kInPlace>
  EIGEN_ALWAYS_INLINE void flow_pass(int k, const State& from, const State& to,
                                     double* __restrict Q) {
    const auto cos = values(flows_.cos(k)), cm1 = values(flows_.cm1(k));
    const auto sinc = values(flows_.sinc(k)), msinc = values(flows_.msinc(k));
    double* __restrict q = lanes(to.q);
    double* __restrict p = lanes(to.p);
    double* __restrict eq = lanes(to.eq);
    double* __restrict ep = lanes(to.ep);
    const double* __restrict q_in = kInPlace ? nullptr : lanes(from.q);
    const double* __restrict p_in = kInPlace ? nullptr : lanes(from.p);
    const double* __restrict eq_in = kInPlace ? nullptr : lanes(from.eq);
    const double* __restrict ep_in = kInPlace ? nullptr : lanes(from.ep);
    for (Eigen::Index e = 0; e < n(); ++e) {
      const double c = at(cos, e), cm = at(cm1, e), sc = at(sinc, e), ms = at(msinc, e);
      for (int l = 0; l < kLanes; ++l) {
        const Eigen::Index x = kLanes * e + l;
        double qx = kInPlace ? q[x] : q_in[x], px = kInPlace ? p[x] : p_in[x];
        double eqx = kKahan ? (kInPlace ? eq[x] : eq_in[x]) : 0;
        double epx = kKahan ? (kInPlace ? ep[x] : ep_in[x]) : 0;
        flow_update<kKahan>(c, cm, sc, ms, qx, px, eqx, epx);
        q[x] = qx, p[x] = px;
        if (kKahan) eq[x] = eqx, ep[x] = epx;
        if constexpr (kIdentity)
          if (Q) Q[x] = qx;
      }
    }
  }
  // (Fixed dimension: in place, whole arrays.)
  template <bool kKahan>
  EIGEN_ALWAYS_INLINE void flow(int k, const Values&, Values& v, double* Q) {
    flow_update<kKahan>(fixed(flows_.cos(k)), fixed(flows_.cm1(k)), fixed(flows_.sinc(k)),
                        fixed(flows_.msinc(k)), v.q, v.p, v.eq, v.ep);
    if (Q)
      for (int e = 0; e < D; ++e) Q[e] = v.q[e];
  }

  // The kick p -= hd g from `from` to `to` (in place when they are the same); g also to save
  // when given.
  template <bool kKahan>
  EIGEN_ALWAYS_INLINE void kick(double hd, const Scalar* g, const State& from, State& to,
                                Scalar* save) {
    if (&from == &to) {
      kick_pass<kKahan, true>(hd, lanes(g), from, to, save ? lanes(save) : nullptr);
    } else {
      kick_pass<kKahan, false>(hd, lanes(g), from, to, save ? lanes(save) : nullptr);
      std::copy_n(from.q, n(), to.q);
      if (kKahan) std::copy_n(from.eq, n(), to.eq);
    }
  }
  template <bool kKahan, bool kInPlace>
  EIGEN_ALWAYS_INLINE void kick_pass(double hd, const double* __restrict g, const State& from,
                                     const State& to, double* __restrict save) {
    double* __restrict p = lanes(to.p);
    double* __restrict ep = lanes(to.ep);
    const double* __restrict p_in = kInPlace ? nullptr : lanes(from.p);
    const double* __restrict ep_in = kInPlace ? nullptr : lanes(from.ep);
    for (Eigen::Index x = 0; x < kLanes * n(); ++x) {
      double q = 0, px = kInPlace ? p[x] : p_in[x], eq = 0;
      double epx = kKahan ? (kInPlace ? ep[x] : ep_in[x]) : 0;
      kick_update<kKahan>(-hd * g[x], q, px, eq, epx);
      p[x] = px;
      if (kKahan) ep[x] = epx;
      if (save) save[x] = g[x];
    }
  }
  template <bool kKahan>
  EIGEN_ALWAYS_INLINE void kick(double hd, const Scalar* g, const Values&, Values& v,
                                Scalar* save) {
    Fixed ge;
    for (int e = 0; e < D; ++e) ge[e] = g[e];
    kick_update<kKahan>(Fixed(-hd * ge), v.q, v.p, v.eq, v.ep);
    if (save)
      for (int e = 0; e < D; ++e) save[e] = g[e];
  }

  // The force at the stage q (eigen coordinates; already in Q_ when have_Q), evaluated in
  // physical coordinates: in eigen coordinates in G_, or (identity basis) in g_.
  EIGEN_ALWAYS_INLINE const Scalar* evaluate(const Scalar* q, bool have_Q, int i,
                                             long& evaluations) {
    if constexpr (kIdentity) {
      if (!have_Q) std::copy_n(q, n(), Q_.data());
    } else {
      transform_.inverse(ConstMap(q, m_), Q_);
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
    if constexpr (kFixed)
      return D;
    else
      return m_;
  }

  // A coefficient's values for the passes: the one value (scalar M) or a pointer to the array.
  static double values(double value) { return value; }
  template <class Map>
  static const double* values(const Map& map) {
    return map.data();
  }
  static double at(double value, Eigen::Index) { return value; }
  static double at(const double* values, Eigen::Index e) { return values[e]; }
  // A coefficient as a fixed-size array (or the one value of a scalar M).
  static double fixed(double value) { return value; }
  template <class Map>
  static Fixed fixed(const Map& values) {
    return Fixed(values.data());
  }

  // Slot k of the storage (the second copy's slots 6..9 exist with a dynamic dimension only).
  Scalar* slot(int k) { return k < kArrays ? spectral_.data() + k * stride_ : nullptr; }
  SpectralMap map(Scalar* x) const { return {x, m_}; }

  Method method_;
  System system_;
  bool kahan_, rkn_;
  int s_;
  bool fsal_;
  Eigen::Index d_;
  double h_;  // (the kicks' h d_i are formed as they are used)
  FlowCoefficients<Coef> flows_;
  Transform transform_;
  MOperator M_;
  // kArrays arrays in eigen coordinates, m_ entries each and stride_ apart.
  Eigen::Index m_, stride_;
  Storage spectral_;
  State state_;
  Scalar *G_, *G_last_;
  State work_;                  // (dynamic dimension only)
  Eigen::VectorXd Q_, g_, Mq_;  // physical coordinates (Q_, g_ go to the callback)
  bool have_history_ = false;
  bool pending_ = false;  // the stored state awaits flow s (the last of the step)
  StepPlace place_{&method_, 0, 0};
};

}  // namespace erkn::detail
