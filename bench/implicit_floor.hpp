// The loop a specialist writes for one implicit ERKN or RKN method at a fixed small dimension D
// with a scalar or diagonal M (issue 17: the floor of an implicit stage's CPU per grad U). Eq. (d)
// (docs: DESIGN.md §1), per eigen coordinate k with v_k = h^2 lambda_k:
//   Q_i     = phi0(c_i^2 v) q + h c_i phi1(c_i^2 v) p - sum_{j<=i} h^2 abar_ij(v) f(Q_j)
//   q_{n+1} = phi0(v) q + h phi1(v) p - sum_i h^2 bbar_i(v) f(Q_i)
//   p_{n+1} = -h lambda phi1(v) q + phi0(v) p - sum_i h b_i(v) f(Q_i)
// with f = grad U (ERKN) or, for the RKN limits (v = 0), f = grad U + lambda Q.
// The coefficients are read once at setup through erkn::Method::evaluate (the generator's
// emitted functions) and the method's c; the phi's are cos x and sin x / x, x = sqrt(v). Nothing
// else is taken from erkn's runtime. S (stages) and D are template parameters, so every loop over
// stages and coordinates unrolls; the state and the stage values are fixed-size arrays in
// registers; the gradient is a functor g(Q, out) on Eigen::Array<double, D, 1>, inlined, or
// Callback: erkn::System::gradient (a std::function on Eigen::VectorXd), as erkn calls it.
//
// Stage solve (same tests and constants as erkn's stage_fixed_point.hpp):
//   - start: Q_0 = r_i - h^2 abar_ii g_pred, g_pred the Lagrange extrapolation at c_i through
//     stage i's `order` most recent stage forces (this step's j < i at c_j, the previous step's
//     at c_j - 1; a time already taken is skipped); the order fixed per method (Settings);
//   - iterate Q <- r_i - h^2 abar_ii f(Q); delta^2 = |dQ|^2 / max(|Q_new|^2, |Q|^2);
//   - converged at an iteration it >= 2 when theta / (1 - theta) delta <= tol (theta = delta /
//     delta_old), or when dQ = 0; failed (throws) when theta >= max_theta above round-off or
//     after max_iterations;
//   - the first iteration stops when theta_s / (1 - theta_s) delta weight_i <= kFirstShare tol,
//     theta_s = kThetaSafety theta (theta measured at the stage's last second iteration,
//     |h^2 abar_ii (f(Q_1) - f(Q_0))| / |Q_1 - Q_0|), weight_i = max(1, |bbar_i / abar_ii|,
//     |b_i / (h abar_ii)|), and the measurement younger than kThetaRefresh solves;
//   - the stage's force is the one at the last iterate but one (no confirming evaluation).
// Left out against erkn: Newton fallback (a stage that fails throws), the predictor's adaptive
// order, the extra iterations after a cold start (reset_tightening), too_slow, in_range's
// rescaling of extreme norms, statistics beyond the evaluation count; compensated summation and
// the finiteness checks only on request (Settings; erkn_implicit_floor times both ways).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <erkn/erkn.hpp>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>

namespace bench::floor {

struct Settings {
  double tolerance = 1e-14, roundoff_level = 1e-12, max_theta = 0.9;  // erkn's Options defaults
  int max_iterations = 30;
  int order = 0;  // predictor nodes per stage (0: every node, as erkn starts)
  // Two of erkn's extras, to measure what they cost: Kahan-compensated q += dq, p += dp (erkn's
  // default, compensated_sum.hpp's form), and finiteness checks as erkn makes them at a fixed D
  // (each iterate's |Q_new|^2, which the test sums anyway, and the step's result; throws).
  bool compensated = false, checks = false;
};

/// x as a value of its own: the empty asm keeps GCC from merging adjacent entries into one
/// vector load or store. (A vector store read back by a scalar load of its upper half, or a vector
/// load spanning two scalar stores, is not forwarded from the store buffer on this machine: at P3
/// the loop's force, written entry by entry by the gradient and read as one vector, stalled there,
/// and at P2 the copy of the stage forces G_ (two 8-byte stores) to G_old_ as one 16-byte load:
/// perf. Kept apart: SERKN2s3 P2 15.7 -> 12.1 ns per grad U, stand-alone.)
[[gnu::always_inline]] inline double one_entry(double x) {
#if defined(__GNUC__) && defined(__x86_64__)
  asm("" : "+x"(x));
#endif
  return x;
}

/// erkn::System::gradient called as erkn calls it: Q copied into an Eigen::VectorXd, g read back
/// (Loop::force reads it entry by entry; the stores into q, merged by GCC into one vector store,
/// cost nothing measurable when kept apart by a compiler barrier: P3, SERKN2s3, stand-alone).
template <int D>
struct Callback {
  std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)> f;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(D), g = Eigen::VectorXd::Zero(D);
  [[gnu::always_inline]] void operator()(const Eigen::Array<double, D, 1>& Q,
                                         Eigen::Array<double, D, 1>& out) {
    for (int k = 0; k < D; ++k) q[k] = Q[k];
    f(q, g);
    for (int k = 0; k < D; ++k) out[k] = g[k];
  }
};

/// kCarry: the next step's first Q_0 formed at the end of a step (next_guess), and stored stage
/// forces read entry by entry (stored()).
template <int S, int D, class Gradient, bool kCarry = false>
class Loop {
 public:
  using Arr = Eigen::Array<double, D, 1>;

  Loop(const erkn::Method& m, const Arr& lambda, double h, Gradient g, const Arr& q0, const Arr& p0,
       const Settings& settings = {})
      : g_(std::move(g)), lambda_(lambda), set_(settings), q_(q0), p_(p0) {
    if (m.stages() != S || m.is_explicit() || h <= 0)
      throw std::invalid_argument("floor::Loop: an implicit method of S stages and h > 0");
    rkn_ = m.kind() == erkn::Kind::rkn;
    for (int k = 0; k < D; ++k) set_coordinate(m, h, k);
    for (int i = 0; i < S; ++i) {
      explicit_[i] = (A_[i][i] == 0).all();
      weight_[i] = 1;
      for (int k = 0; k < D; ++k)
        if (!explicit_[i])
          weight_[i] = std::max({weight_[i], std::abs(bq_[i][k] / A_[i][i][k]),
                                 std::abs(h * bp_[i][k] / A_[i][i][k])});
      set_nodes(m.table().c, i);
    }
  }
  Loop(const Loop&) = delete;  // (node_ points into the object)

  /// n steps (everything but the gradient's std::function inlined into the loop).
  [[gnu::flatten]] void run(long n) {
    for (long step = 0; step < n; ++step) this->step();
  }
  const Arr& q() const { return q_; }
  const Arr& p() const { return p_; }
  long evaluations() const { return evaluations_; }

 private:
  // Coordinate k's coefficients at v = h^2 lambda_k (0 for the RKN limits).
  void set_coordinate(const erkn::Method& m, double h, int k) {
    const double v = rkn_ ? 0.0 : h * h * lambda_[k], x = std::sqrt(v);
    const auto phi0 = [](double w) { return std::cos(std::sqrt(w)); };
    const auto phi1 = [](double w) { return w == 0 ? 1.0 : std::sin(std::sqrt(w)) / std::sqrt(w); };
    std::array<double, erkn::kMaxStages> b{}, bbar{};
    std::array<double, erkn::Coefficients::kMaxPacked> abar{};
    m.evaluate(v, b.data(), bbar.data(), abar.data());
    for (int i = 0; i < S; ++i) {
      const double c = m.table().c[i];
      phi0c_[i][k] = phi0(c * c * v), hcphi1c_[i][k] = h * c * phi1(c * c * v);
      bq_[i][k] = h * h * bbar[i], bp_[i][k] = h * b[i];
      for (int j = 0; j <= i; ++j) A_[i][j][k] = h * h * abar[erkn::Coefficients::packed(i, j)];
    }
    phi0_[k] = std::cos(x), hphi1_[k] = h * phi1(v);
    mhMphi1_[k] = rkn_ ? 0.0 : -h * lambda_[k] * phi1(v);
  }

  // Stage i's nodes, most recent first (this step's j < i, then the previous step's), and the
  // Lagrange weights at c_i of the first `used` of them, with and without the previous step.
  void set_nodes(const double* c, int i) {
    std::array<double, 2 * S> times{};
    int n = 0, current = 0;
    for (int age = 0; age <= 1; ++age)
      for (int j = (age == 0 ? i : S) - 1; j >= 0; --j) {
        const double t = c[j] - age;
        if (std::find(times.begin(), times.begin() + n, t) != times.begin() + n) continue;
        times[n] = t, node_[i][n] = age == 0 ? &G_[j] : &G_old_[j], ++n;
        current += age == 0;
      }
    used_[i] = set_.order > 0 ? std::min(set_.order, n) : n;
    first_used_[i] = std::min(used_[i], current);
    lagrange(times.data(), used_[i], c[i], w_[i].data());
    lagrange(times.data(), first_used_[i], c[i], w_first_[i].data());
  }
  static void lagrange(const double* t, int m, double at, double* w) {
    for (int l = 0; l < m; ++l) {
      w[l] = 1;
      for (int k = 0; k < m; ++k)
        if (k != l) w[l] *= (at - t[k]) / (t[l] - t[k]);
    }
  }

  void step() {
    for (int i = 0; i < S; ++i) stage(i);
    Arr dq = (phi0_ - 1) * q_ + hphi1_ * p_, dp = mhMphi1_ * q_ + (phi0_ - 1) * p_;
    for (int i = 0; i + 1 < S; ++i) {
      const Arr g = stored(G_[i]);
      dq -= bq_[i] * g, dp -= bp_[i] * g;
    }
    for (int i = 0; i < S; ++i)  // (entry by entry: G_ was stored so, one_entry)
      for (int k = 0; k < D; ++k) G_old_[i][k] = one_entry(G_[i][k]);
    const Arr g = stored(G_[S - 1]);
    if constexpr (kCarry) next_guess_ = next_guess(q_ + dq, p_ + dp, g);
    dq -= bq_[S - 1] * g, dp -= bp_[S - 1] * g;
    if (set_.checks && !std::isfinite((dq + dp).square().sum()))
      throw std::runtime_error("floor::Loop: non-finite step");
    if (set_.compensated) {
      add(q_, eq_, dq), add(p_, ep_, dp);
    } else {
      q_ += dq, p_ += dp;
    }
    history_ = true;
  }

  // The next step's first iterate Q_0 of stage 1 (a guess: any reassociation is harmless), one
  // multiply-subtract after this step's last stage force g, as stage() forms Q_0 after G_{i-1}:
  // with (q, p) the new state without g's terms, Q_0 = phi0c_1 (q - h^2 bbar_s g) + hcphi1c_1
  // (p - h b_s g) - h^2 abar_11 (rest + w_0 g), rest the guess's other nodes (G_old_ = this
  // step's).
  Arr next_guess(const Arr& q, const Arr& p, const Arr& g) const {
    Arr rest = Arr::Zero();
    for (int l = used_[0] - 1; l >= 1; --l) rest += w_[0][l] * stored(*node_[0][l]);
    const Arr combined = phi0c_[0] * bq_[S - 1] + hcphi1c_[0] * bp_[S - 1] + A_[0][0] * w_[0][0];
    return (phi0c_[0] * q + hcphi1c_[0] * p - A_[0][0] * rest) - combined * g;
  }

  // A stored stage force; with kCarry read entry by entry (one_entry: GCC otherwise loaded
  // adjacent entries, or adjacent stages' entries at D = 1, as one vector over separate stores).
  static Arr stored(const Arr& a) {
    if constexpr (!kCarry) return a;
    Arr v;
    for (int k = 0; k < D; ++k) v[k] = one_entry(a[k]);
    return v;
  }

  // x += dx, Kahan-compensated: e carries the low-order bits lost by earlier updates.
  static void add(Arr& x, Arr& e, Arr dx) {
    dx += e;
    e = x;
    x += dx;
    e = (e - x) + dx;
  }

  // f(Q), its entries read one by one (one_entry).
  Arr force(const Arr& Q) {
    ++evaluations_;
    Arr f, out;
    g_(Q, f);
    for (int k = 0; k < D; ++k) out[k] = one_entry(f[k]);
    if (rkn_) out += lambda_ * Q;
    return out;
  }

  // Stage i, with Q_0 one multiply-subtract after the newest known force G_{i-1}: it enters r_i
  // and the guess's first node (i > 0), so both sums take it last and Q_0 takes it once, with the
  // coefficients combined, h^2 (abar_{i,i-1} + abar_ii w_0). (The rest of the sums does not wait
  // for it.)
  void stage(int i) {
    Arr base = phi0c_[i] * q_ + hcphi1c_[i] * p_;
    for (int j = 0; j + 1 < i; ++j) base -= A_[i][j] * stored(G_[j]);
    if (explicit_[i]) {
      G_[i] = force(i > 0 ? Arr(base - A_[i][i - 1] * G_[i - 1]) : base);
      return;
    }
    if (kCarry && i == 0 && history_) {  // (Q_0 formed by the step before: next_guess)
      G_[0] = fixed_point(0, base, next_guess_);
      return;
    }
    const int n = history_ ? used_[i] : first_used_[i], newest = i > 0 ? 1 : 0;
    const double* w = history_ ? w_[i].data() : w_first_[i].data();
    Arr rest = Arr::Zero();  // the guess without this step's G_{i-1}
    for (int l = n - 1; l >= newest; --l) rest += w[l] * stored(*node_[i][l]);
    if (i == 0) {
      G_[i] = fixed_point(i, base, base - A_[i][i] * rest);
      return;
    }
    const Arr g = stored(G_[i - 1]);
    const Arr combined = A_[i][i - 1] + A_[i][i] * w[0];
    G_[i] = fixed_point(i, base - A_[i][i - 1] * g, (base - A_[i][i] * rest) - combined * g);
  }

  // The stage's fixed point from Q_0; returns its force (at the last iterate but one).
  Arr fixed_point(int i, const Arr& r, Arr Q) {
    const Arr& A = A_[i][i];
    Arr g = force(Q), Q_new = r - A * g;
    double X = (Q_new - Q).square().sum(), N = std::max(Q_new.square().sum(), Q.square().sum());
    if (set_.checks && !std::isfinite(N)) throw std::runtime_error("floor::Loop: non-finite");
    Record& rec = record_[i];
    rec.age += rec.age < kThetaRefresh;
    if (X > 0 && rec.age < kThetaRefresh && X * rec.proof_X <= rec.proof_N * N) return g;
    const double first2 = X, delta_first = std::sqrt(X / N);
    double delta_old = delta_first;
    const Arr g_first = g;
    for (int it = 2; it <= set_.max_iterations; ++it) {
      const double norm2_Q = Q_new.square().sum();
      Q = Q_new, g = force(Q), Q_new = r - A * g;
      X = (Q_new - Q).square().sum(), N = std::max(Q_new.square().sum(), norm2_Q);
      if (set_.checks && !std::isfinite(N)) throw std::runtime_error("floor::Loop: non-finite");
      if (it == 2 && first2 > 0) record(i, first2, X, N, delta_first, A * (g - g_first));
      if (X == 0 || within(X, N, delta_old)) return g;
      const bool noise = X <= set_.roundoff_level * set_.roundoff_level * N;
      if (X >= set_.max_theta * set_.max_theta * delta_old * delta_old * N) {
        if (noise) return g;
        throw std::runtime_error("floor::Loop: stage does not contract");
      }
      delta_old = std::sqrt(X / N);
    }
    if (X <= set_.roundoff_level * set_.roundoff_level * N) return g;
    throw std::runtime_error("floor::Loop: stage not converged");
  }

  // theta / (1 - theta) delta <= tol, theta = delta / delta_old, multiplied out (erkn's within).
  bool within(double X, double N, double delta_old) const {
    const double tol = set_.tolerance, R = tol * delta_old * N - X;
    return R >= 0 && tol * tol * X * N <= R * R;
  }

  // The second iteration's theta measurement (or, below 1e3 round-offs, the old theta renewed
  // when the updates' ratio does not exceed what it allowed).
  void record(int i, double first2, double X, double N, double delta_first, const Arr& dg) {
    Record& rec = record_[i];
    constexpr double eps = std::numeric_limits<double>::epsilon();
    if (delta_first < 1e3 * eps) {
      const double bound = kThetaSafety * rec.theta * delta_first;
      if (rec.theta >= 0 && (X == 0 ? eps <= bound : X <= bound * bound * N)) rec.age = 0;
      return;
    }
    rec.theta = std::sqrt(dg.square().sum() / first2), rec.age = 0;
    const double ts = kThetaSafety * rec.theta, lhs = ts * weight_[i],
                 rhs = kFirstShare * set_.tolerance * (1 - ts);
    rec.proof_X = lhs * lhs, rec.proof_N = ts < 0.5 ? rhs * rhs : -1;
  }

  static constexpr double kThetaSafety = 4, kFirstShare = 0.01;
  static constexpr int kThetaRefresh = 8;
  struct Record {
    double theta = -1, proof_X = 0, proof_N = -1;
    int age = 0;
  };

  Gradient g_;
  Arr lambda_;
  Settings set_;
  bool rkn_ = false, history_ = false;
  Arr q_, p_, eq_ = Arr::Zero(), ep_ = Arr::Zero(), phi0_, hphi1_, mhMphi1_, next_guess_;
  std::array<Arr, S> phi0c_, hcphi1c_, bq_, bp_, G_, G_old_;
  std::array<std::array<Arr, S>, S> A_;
  std::array<std::array<const Arr*, 2 * S>, S> node_{};
  std::array<std::array<double, 2 * S>, S> w_{}, w_first_{};
  std::array<int, S> used_{}, first_used_{};
  std::array<bool, S> explicit_{};
  std::array<double, S> weight_{};
  std::array<Record, S> record_{};
  long evaluations_ = 0;
};

/// f(loop) with a Loop<S, D, Gradient, kCarry> of m's stage count S (1..kMaxImplicitStages)
/// constructed from the arguments; returns f's result.
inline constexpr int kMaxImplicitStages = 4;
template <int D, class Gradient, class F, int S = 1, bool kCarry = false>
auto with_loop(const erkn::Method& m, const Eigen::Array<double, D, 1>& lambda, double h,
               const Gradient& g, const Eigen::Array<double, D, 1>& q0,
               const Eigen::Array<double, D, 1>& p0, const Settings& settings, F&& f) {
  if (m.stages() == S) {
    Loop<S, D, Gradient, kCarry> loop(m, lambda, h, g, q0, p0, settings);
    return f(loop);
  }
  if constexpr (S < kMaxImplicitStages)
    return with_loop<D, Gradient, F, S + 1, kCarry>(m, lambda, h, g, q0, p0, settings,
                                                    std::forward<F>(f));
  throw std::invalid_argument("floor::with_loop: more stages than kMaxImplicitStages");
}

}  // namespace bench::floor
