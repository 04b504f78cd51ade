// The stages of eq. (d), Q_i = r_i - h^2 abar_ii(V) g(Q_i), solved one by one, written once over
// a space (serial_space.hpp: one process; mpi/src/slab_space.hpp: a grid distributed over MPI
// ranks): fixed-point iteration from predicted starting values (stage_predictor.hpp), stopped by
// the contraction theta (also at the first iteration once theta is known), and Newton when it
// fails: a dense LU for small d, matrix-free Newton-Krylov (GMRES) beyond (stage_newton.hpp).
// Stages run in eigen coordinates; gradients are evaluated in physical coordinates. Every norm
// and decision comes from the space's reduce, so all processes of a space decide alike.
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
#include <type_traits>
#include <utility>

#include "block_pool.hpp"
#include "erkn/error.hpp"
#include "erkn/integrator.hpp"
#include "format.hpp"
#include "gmres.hpp"
#include "stage_checks.hpp"
#include "stage_predictor.hpp"
#include "step_coefficients.hpp"
#include "stepper_base.hpp"

namespace erkn::detail {

template <class Space, class Coef>
class StageSolver {
 public:
  using Map = typename Space::Map;

  /// The solver refers to method, system, options, space and k (owned by the stepper).
  StageSolver(const Method& method, const System& system, const Options& options, Space& space,
              const StepCoefficients<Coef>& k);
  StageSolver(const StageSolver&) = delete;  // (the maps view its own buffers)
  StageSolver& operator=(const StageSolver&) = delete;

  /// Solves the stages of the step from (q_hat, p_hat) (eigen coordinates); G(i) then holds stage
  /// i's gradient in eigen coordinates. Returns the fixed point's gradient evaluations, each one a
  /// stage iteration (count() adds them, and Newton's counts, once the step has succeeded);
  /// throws erkn::Error naming the stage.
  template <class State>
  long solve(const State& q_hat, const State& p_hat, const StepPlace& at) {
    return solve_inline<0>(q_hat, p_hat, at);
  }
  /// solve, inlined into the caller (the fixed-D step: as a call, its frame and its loop's
  /// set-up were ~45 instructions per step, P2); S: the stage count when the caller knows it at
  /// compile time (for_each_stage), else 0.
  template <int S, class State>
  [[gnu::always_inline]] long solve_inline(const State& q_hat, const State& p_hat,
                                           const StepPlace& at);
  /// f(i) for the stages i = 0, ..., s - 1 in order: with S = s > 0 one inlined call per stage
  /// with i a constant, so that each stage's coefficients, records and arrays are found at
  /// constant offsets (with a fixed Coef, StepCoefficients::layout_s); else a loop.
  template <int S, class F>
  [[gnu::always_inline]] void for_each_stage(F&& f) const {
    if constexpr (S > 0) {
      const auto each = [&]<int... I>(std::integer_sequence<int, I...>) { (f(I), ...); };
      each(std::make_integer_sequence<int, S>{});
    } else {
      for (int i = 0; i < s_; ++i) f(i);
    }
  }
  /// Adds a solved step's counts to stats: `evaluations` (solve's result) as gradient evaluations
  /// and as stage iterations, and those of its Newton fallbacks. (One counter on the fixed point's
  /// path, not five cleared and added per step: GCC added two adjacent ones with one 16-byte load
  /// spanning two 8-byte stores, which this AMD EPYC does not store-forward.)
  [[gnu::always_inline]] void count(long evaluations, Statistics& stats) {
    stats.gradient_evaluations += evaluations;
    stats.stage_iterations += evaluations;
    if (newton_pending_) add_newton_counts(stats);
  }
  Map G(int i) { return predictor_.G(i); }
  /// After a successful step (its gradients start the next step's guesses); S as solve_inline's.
  template <int S = 0>
  void advance() {
    predictor_.template advance<S>();
  }
  /// Forgets the steps before (set_state).
  void reset() {
    predictor_.reset();
    carried_for_ = -1;
  }
  template <class X, class B>
  void carry(int last, const X& q_part, const X& p_part, const B& h2bbar_last, const B& hb_last);

 private:
  // The fixed point's iterates, force and contraction measure: with a fixed D values, which the
  // compiler keeps in registers (spilled to the stack around the user's gradient only), else
  // views of x_'s arrays. (Through views into x_ every iteration stored and reloaded its arrays
  // and their pointers: P2, P3.)
  using Work = std::conditional_t<Space::kFixed, typename Space::Array, Map>;
  // The arrays of one stage: r_i, the iterate Q (eigen coordinates and physical), the next one,
  // the starting guess's gradient, g(Q_0) of the first iteration, g at the iterate.
  struct Arrays {
    alignas(EIGEN_MAX_ALIGN_BYTES) typename Space::template Block<5> block;
    Map r_hat, Q_hat, Q_hat_new, guess_hat, g_first_hat;
    // (Go to the callbacks. Q not cleared: every path writes it before a call, start_stage; Zero
    // was a calloc, which glibc's per-thread cache does not serve. g cleared, after its malloc: a
    // gradient that leaves an entry unwritten finds it 0. Its calloc took _int_malloc and, the
    // cache's bin then full, a free through _int_free per construction: ~3 % of the time of a
    // construct + 1-step run of SERKN2s3 at P3, perf.) Both kept for this thread's next stage
    // solver (block_pool.hpp).
    Eigen::VectorXd Q, g;
    ~Arrays() { give_kept_vectors(Q, g); }
  };
  // What the solver knows of stage i between steps: kFresh before its first solve. (Trivial, so
  // that record_ is not cleared: the constructor sets the s records read. Value-initialised, the
  // kMaxStages records were a 1 KB rep stos, ~1.9 % of the time of a construct + 1-step run of
  // SERKN2s3 at P3: perf.)
  struct StageRecord {
    double theta;               // the contraction measured; < 0: none
    double due_num2, due_den2;  // a new measurement, theta^2 as a fraction; 0: none
    int theta_age;              // stage solves since the measurement, at most kThetaRefresh
    double weight;              // max(1, |bbar_i| / |abar_ii|, |b_i| / (h |abar_ii|))
    double newton_cost;         // evaluations of its last Newton solve; 0: none
    bool explicit_stage;        // abar_ii = 0: Q_i = r_i, one evaluation
    // contraction_proves' factors, formed with theta (set_theta): (theta_s weight)^2 and
    // (kFirstShare tolerance (1 - theta_s))^2, or -1 where no first-iteration stop is allowed
    // (no theta, theta_s >= 1/2).
    double proof_X, proof_N;
  };
  static constexpr StageRecord kFresh{.theta = -1,
                                      .due_num2 = 0,
                                      .due_den2 = 0,
                                      .theta_age = 0,
                                      .weight = 0,
                                      .newton_cost = 0,
                                      .explicit_stage = false,
                                      .proof_X = 0,
                                      .proof_N = -1};
  // Newton's workspace (allocated at the first fallback): dense (d <= kDenseNewtonMaxD) or
  // Newton-Krylov.
  struct NewtonWork {
    Eigen::VectorXd r, F, gU, col, Q_new;
    typename Space::Spectral col_hat;
    Eigen::MatrixXd J, H, M_dense;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  };
  struct KrylovWork {
    Eigen::VectorXd Qe, ge;
    Eigen::ArrayXd precond;
    std::optional<Gmres> gmres;
  };

  // A fixed-point iteration's change: X = |dQ|^2, N = the larger squared norm of the two
  // iterates (delta^2 = X / N), or (delta^2, 1) at extreme norms (in_range).
  struct Change {
    double X, N;
  };
  enum class Verdict { iterate, converged, failed };

  // Stage i: inlined into solve with a fixed D (as calls, their frames and the reloads of what
  // they read through members were ~80 instructions per stage, P2), one call otherwise.
  // (evaluations: the fixed point's count, solve's result.)
  template <class State>
  [[gnu::always_inline]] void stage(int i, const State& q_hat, const State& p_hat,
                                    long& evaluations) {
    solve_stage(i, start_stage(i, q_hat, p_hat), evaluations);
  }
  template <class State>
  [[gnu::noinline]] void stage_call(int i, const State& q_hat, const State& p_hat,
                                    long& evaluations) {
    stage(i, q_hat, p_hat, evaluations);
  }
  // A stage's r_i and starting iterate Q_0 (start_stage): with a fixed D values, which the
  // fixed point takes in registers (stored to x_ and loaded back, they and the arrays' addresses
  // were ~20 instructions per stage, P3), else views of x_.r_hat and x_.Q_hat; and h^2 abar_ii(V)
  // as the arrays see it (its slot's address formed once per stage).
  using Abar = decltype(Space::co(std::declval<const StepCoefficients<Coef>&>().abar(0, 0)));
  // (norm2_Q: with kStagedIterate |Q_0|^2, which start_stage's pass forms.)
  struct Start {
    Work r_hat, Q_hat;
    Abar abar_ii;
    double norm2_Q = 0;
  };
  void solve_stage(int i, const Start& start, long& evaluations);
  [[gnu::noinline, gnu::cold]] void fall_back(int i, const Start& start);
  [[gnu::noinline, gnu::cold]] void add_newton_counts(Statistics& stats);
  template <class State>
  Start start_stage(int i, const State& q_hat, const State& p_hat);
  template <class State>
  void start_fixed(int i, const State& q_hat, const State& p_hat, Start& s);
  // The fixed point's arrays: with a fixed D values (Work), else views of x_'s (the iterates,
  // the next, the force, g(Q_0) of the first iteration), G(i) and h^2 abar_ii, held in locals:
  // after each call of the user's gradient the compiler reloads what it reads through members.
  // (finite_Q: with kSumChecks, the iterate is known finite; checked_iterate.)
  struct Iterates {
    Work r_hat, Q_hat, Q_hat_new, G, g_first_hat;
    Map G_i;
    Abar abar_ii;
    bool finite_Q = false;
  };
  bool fixed_point(int i, const Start& start, long& evaluations);
  std::array<double, 2> iterate(int i, int it, Iterates& x, long& evaluations);
  std::array<double, 2> next_iterate(Iterates& x);
  bool checked_iterate(int i, double norm2_Q_new) const;
  // Whether the space takes the iterate in one pass that stages it (SerialSpace::iterate).
  static constexpr bool kStagedIterate = [] {
    if constexpr (requires { Space::kStagedIterate; })
      return Space::kStagedIterate;
    else
      return false;
  }();
  // Whether the fixed point checks g and the next iterate on |Q_new|^2 (checked_iterate) rather
  // than scanning them around each call of the gradient: with a staged iterate, and with a fixed D
  // (P3: with the first iterate's check packed, all_finite_values, -6 % CPU per grad U against
  // the scans, median over the implicit methods, A/B in one process).
  static constexpr bool kSumChecks = kStagedIterate || Space::kFixed;
  bool iterate_on(int i, Iterates& x, Change c, double first2, double norm2_Q, long& evaluations);
  [[gnu::noinline]] bool fixed_point_call(int i, const Start& start, long& evaluations) {
    return fixed_point(i, start, evaluations);
  }
  void keep_iterate(const Work& Q_hat);
  Verdict verdict(int i, int it, Change c, double& delta_old, int& extra) const;
  static bool within(Change c, double delta_old, double tol);
  static Change in_range(double change2, double norm2);
  bool reset_tightening(Change c, double delta_old, int& extra) const;
  static double relative_change2(double change2, double norm2);
  bool too_slow(int i, int it, double theta, double delta_old) const;
  bool contraction_proves(int i, Change c);
  void set_theta(StageRecord& r, double theta) const;
  static bool measures_contraction(double delta_first);
  void record_contraction(int i, double first2, Change c, double delta_first, double measure2);
  static double square(double x) { return x * x; }
  // A stage's starting iterate Q_0 = r_i - h^2 abar_ii g_pred (every path's: start_stage,
  // start_fixed's stage 0, Newton's start).
  template <class R, class A, class P>
  static auto first_iterate(const R& r_hat, const A& abar_ii, const P& guess) {
    return r_hat - abar_ii * guess;
  }

  // stage_newton.hpp
  void newton(int i, Statistics& stats);
  void start_newton(int i);
  bool newton_converged(double delta, double delta_old, int it) const;
  void check_contraction(int i, const char* solver, double delta, double delta_old, int it,
                         int& stalls, double residual) const;
  [[noreturn]] void not_converged(int i, double residual, int iterations,
                                  const std::string& why = "") const;
  void start_newton_krylov(int i);
  void newton_krylov(int i, Statistics& stats);
  int krylov_iteration(int i, int it, double& delta_old, int& stalls, double& residual,
                       bool& sigma_pending, Statistics& stats);
  void apply_abar(int i, const Eigen::VectorXd& x, Eigen::VectorXd& out);
  template <class V>
  void jacobian_times(int i, const V& v, Eigen::VectorXd& Jv, Statistics& stats);
  void set_preconditioner(int i, double sigma);
  void jacobian(int i, Statistics& stats);

  // G_i = the force at the iterate (Q, Q_hat) in eigen coordinates. With kSumChecks the fixed
  // point checks g and Q on its sums instead (finite_Q: Q known finite; checked_iterate). With a
  // fixed D, a Q not known finite is checked on Q_hat (= Q: the identity basis), not on x_.Q:
  // reloaded right after its store, that check waited for it (perf, P3: ~8 % of the samples).
  // (Always inlined: with solve inlined into the step GCC left it out of line at D = 2, P3: +10 %
  // instructions.)
  template <class Y, class G>
  [[gnu::always_inline]] void stage_force(int i, const Y& Q_hat, G&& G_i, long& evaluations,
                                          bool iterate = false, bool finite_Q = false) {
    if constexpr (kStagedIterate) {
      space_.gradient(system_, x_.Q, x_.g, i, *at_, evaluations, !iterate, !finite_Q);
    } else if constexpr (Space::kFixed) {
      if (!finite_Q && !all_finite_values(Q_hat)) non_finite_stage(i, *at_);
      space_.gradient(system_, x_.Q, x_.g, i, *at_, evaluations, !iterate, false);
    } else {
      space_.gradient(system_, x_.Q, x_.g, i, *at_, evaluations);
    }
    space_.to_eigen_force(x_.Q, Q_hat, x_.g, G_i);
  }
  // g = grad U(Q) (+ M Q for RKN methods).
  void force(const Eigen::VectorXd& Q, int i, Statistics& stats) {
    gradient(Q, x_.g, i, stats);
    space_.add_MQ(Q, x_.g);
  }
  void gradient(const Eigen::VectorXd& Q, Eigen::VectorXd& g, int i, Statistics& stats) {
    space_.gradient(system_, Q, g, i, *at_, stats.gradient_evaluations);
  }
  // The square roots of sums over the space (a norm of each vector).
  template <class... V>
  auto norms(const V&... v) const {
    std::array<double, sizeof...(V)> sums =
        space_.reduce(std::array{space_.squared_physical_norm(v)...});
    for (double& x : sums) x = std::sqrt(x);
    return sums;
  }

  // Storage for an array the fixed point writes before it reads: x itself as a view, or a value.
  static Work scratch(const Map& x) {
    if constexpr (Space::kFixed)
      return Work();
    else
      return x;
  }
  // Exchanges the arrays two maps view (Map::swap would exchange their contents), or two values.
  static void swap_views(Map& a, Map& b) {
    auto* const data = a.data();
    new (&a) Map(b.data(), b.size());
    new (&b) Map(data, a.size());
  }
  template <class A>
  static void swap_views(A& a, A& b) {
    std::swap(a, b);
  }

  // Tuning (the comments at their uses say why).
  static constexpr double kThetaSafety = 4, kFirstShare = 0.01;
  static constexpr Eigen::Index kDenseNewtonMaxD = 256;
  static constexpr int kKrylovRestart = 30, kKrylovMaxIterations = 200;
  static constexpr double kKrylovTolerance = 1e-6, kMaxForcing = 0.1, kLinearShare = 0.1;
  static constexpr int kMaxStalls = 2;
  static constexpr double kKeepIterate = 1e-3;
  static constexpr int kThetaRefresh = 8;
  static constexpr double kResetShare = 0.01;
  static constexpr int kResetExtra = 4;
  static constexpr double kEps = std::numeric_limits<double>::epsilon();
  static constexpr double kLowNorm2 = 1e-100, kHighNorm2 = 1e100;  // (in_range)

  const Method& method_;
  int s_;  // stages
  const System& system_;
  const Options& options_;
  Space& space_;
  const StepCoefficients<Coef>& k_;
  StagePredictor<Space> predictor_;
  std::array<StageRecord, kMaxStages> record_;  // (the first s set: the constructor)
  Arrays x_;
  // The step being taken (for messages; solve's argument, kept by address: a copy loaded the
  // caller's separate stores as one wide load, which waits for them to retire).
  const StepPlace* at_ = nullptr;
  // With a fixed D, the next step's first Q_0 of stage 0 (carry) and the step it is for (its
  // number, 1-based; -1: none). A step that fails after carry leaves it for a step number that
  // does not come: its retry has the same number (or set_state rolled the state back: reset).
  std::conditional_t<Space::kFixed, typename Space::Array, bool> next_Q0_{};
  long carried_for_ = -1;
  std::optional<NewtonWork> newton_;
  std::optional<KrylovWork> krylov_;
  // The counts of this step's Newton fallbacks (valid when newton_pending_; cleared by the
  // step's first fallback: a failed step leaves its counts here, uncounted).
  Statistics newton_counts_;
  bool newton_pending_ = false;
};

// max_k |num_k| / |den_k| over the eigen coordinates (numbers or arrays; no allocation; 0 over
// none: a process of a distributed space may hold no coordinates).
template <class A, class B>
double max_ratio(const A& num, const B& den) {
  if constexpr (std::is_same_v<B, double>)
    return std::abs(num) / std::abs(den);
  else
    return num.size() == 0 ? 0.0 : (num.abs() / den.abs()).maxCoeff();
}

template <class Space, class Coef>
StageSolver<Space, Coef>::StageSolver(const Method& method, const System& system,
                                      const Options& options, Space& space,
                                      const StepCoefficients<Coef>& k)
    : method_(method),
      s_(method.stages()),
      system_(system),
      options_(options),
      space_(space),
      k_(k),
      predictor_(method, space),
      x_{space.template block<5>(5),
         space.map(x_.block, 0),
         space.map(x_.block, 1),
         space.map(x_.block, 2),
         space.map(x_.block, 3),
         space.map(x_.block, 4),
         {},
         {}} {
  take_kept_vectors(space.dimension(), x_.Q, x_.g);
  x_.g.setZero();  // (not Zero(d): GCC made that a calloc, see Arrays)
  const int s = method.stages();
  for (int i = 0; i < s; ++i) {
    const auto ratio = [&](const auto& num) {
      return space.reduce_max(max_ratio(num, k.abar(i, i)));
    };
    record_[i] = kFresh;
    record_[i].explicit_stage = explicit_stage(method, i);
    if (!record_[i].explicit_stage)
      record_[i].weight = std::max({1.0, ratio(k.h2bbar(i)), ratio(k.hb(i) * k.h())});
  }
}

// Eq. (d)'s stages one by one.
template <class Space, class Coef>
template <int S, class State>
[[gnu::always_inline]] inline long StageSolver<Space, Coef>::solve_inline(const State& q_hat,
                                                                          const State& p_hat,
                                                                          const StepPlace& at) {
  at_ = &at;
  newton_pending_ = false;
  long evaluations = 0;
  for_each_stage<S>([&](int i) __attribute__((always_inline)) {
    if constexpr (Space::kFixed)
      stage(i, q_hat, p_hat, evaluations);
    else
      stage_call(i, q_hat, p_hat, evaluations);
    if (predictor_.adapt_due(i))
      predictor_.adapt(i, Space::co(k_.abar(i, i)), x_.guess_hat, x_.Q_hat_new, x_.g_first_hat);
  });
  return evaluations;
}

template <class Space, class Coef>
[[gnu::always_inline]] inline void StageSolver<Space, Coef>::solve_stage(int i, const Start& start,
                                                                         long& evaluations) {
  if (record_[i].explicit_stage) {  // (Q = r exactly: its gradient is the stage's; one iteration)
    stage_force(i, start.Q_hat, G(i), evaluations);
    space_.settle();
    return;
  }
  // (With a fixed D the fixed point inlined into the step: its call and frame, and the reloads
  // of what it reads through members, were part of its ~90 instructions per call beyond the
  // iterations, P2.)
  if (!(Space::kFixed ? fixed_point(i, start, evaluations)
                      : fixed_point_call(i, start, evaluations)))
    fall_back(i, start);
}

// Newton where the fixed point failed (from start's r_i), counted into newton_counts_.
template <class Space, class Coef>
void StageSolver<Space, Coef>::fall_back(int i, const Start& start) {
  if constexpr (Space::kFixed) {  // (else start.r_hat views it, and start_stage formed the guess)
    x_.r_hat = start.r_hat;
    predictor_.predict(i, x_.guess_hat);
  }
  if (!newton_pending_) newton_counts_ = Statistics{}, newton_pending_ = true;
  Statistics& stats = newton_counts_;
  ++stats.newton_fallbacks;
  const long before = stats.gradient_evaluations;
  if constexpr (Space::kDenseNewton) {
    if (space_.dimension() <= kDenseNewtonMaxD)
      newton(i, stats);
    else
      newton_krylov(i, stats);
  } else {
    newton_krylov(i, stats);
  }
  space_.settle();  // (the last evaluation's checks)
  record_[i].newton_cost = double(stats.gradient_evaluations - before);
}

// count()'s part for a step with Newton fallbacks.
template <class Space, class Coef>
void StageSolver<Space, Coef>::add_newton_counts(Statistics& stats) {
  const Statistics& n = newton_counts_;
  stats.gradient_evaluations += n.gradient_evaluations;
  stats.hessian_evaluations += n.hessian_evaluations;
  stats.stage_iterations += n.stage_iterations;
  stats.newton_fallbacks += n.newton_fallbacks;
  stats.newton_iterations += n.newton_iterations;
  newton_pending_ = false;
}

// r_i = phi0(c_i^2 V) q + h c_i phi1(c_i^2 V) p - h^2 sum_{j<i} abar_ij g_j, and the starting
// guess Q = r_i - h^2 abar_ii g_pred with g_pred extrapolated from the known stage gradients
// (x_.guess_hat; with a fixed D split, start_fixed); x_.Q (physical) set, x_.r_hat and x_.Q_hat
// too with a dynamic D (with a fixed D fall_back stores r_i and the guess, and keep_iterate the
// iterate Newton-Krylov starts from).
template <class Space, class Coef>
template <class State>
[[gnu::always_inline]] inline auto StageSolver<Space, Coef>::start_stage(int i, const State& q_hat,
                                                                         const State& p_hat)
    -> Start {
  const auto co = [](const auto& value) { return Space::co(value); };
  Start s{scratch(x_.r_hat), scratch(x_.Q_hat), co(k_.abar(i, i))};
  if constexpr (kStagedIterate) {  // (one pass per term, Q_0 staged: SerialSpace::start)
    predictor_.predict(i, x_.guess_hat);
    s.norm2_Q = space_.start(
        i, q_hat, p_hat, k_.phi0c(i), k_.hcphi1c(i), s.abar_ii,
        [&](int j) {
          return std::pair{G(j), k_.abar(i, j)};
        },
        x_.guess_hat, s.r_hat, s.Q_hat);
    space_.to_physical_staged(x_.Q);
    return s;
  }
  if constexpr (Space::kFixed) {
    start_fixed(i, q_hat, p_hat, s);
  } else {
    s.r_hat = co(k_.phi0c(i)) * q_hat + co(k_.hcphi1c(i)) * p_hat;
    for (int j = 0; j < i; ++j) s.r_hat -= co(k_.abar(i, j)) * stored_force(G(j));
    predictor_.predict(i, x_.guess_hat);
    s.Q_hat = first_iterate(s.r_hat, s.abar_ii, x_.guess_hat);
  }
  space_.to_physical(s.Q_hat, x_.Q);
  return s;
}

// start_stage with a fixed D: the same r_i, and Q_0 one multiply-subtract after the newest known
// force G_{i-1} (i > 0), which enters both r_i and the guess (its first node, weight w_0):
// r_i = base - h^2 abar_{i,i-1} G_{i-1}, Q_0 = (base - h^2 abar_ii rest) - h^2 (abar_{i,i-1} +
// abar_ii w_0) G_{i-1}, with base and rest (the guess's other nodes) formed while G_{i-1} is
// evaluated. (Q_0 is a guess: its rounding differs from r_i - h^2 abar_ii g_pred's, which waited
// for G_{i-1} through r_i's last term and the whole prediction. The guess is not kept in
// x_.guess_hat: fall_back and the predictor's adapt form it anew.)
template <class Space, class Coef>
template <class State>
[[gnu::always_inline]] inline void StageSolver<Space, Coef>::start_fixed(int i, const State& q_hat,
                                                                         const State& p_hat,
                                                                         Start& s) {
  const auto co = [](const auto& value) { return Space::co(value); };
  s.r_hat = co(k_.phi0c(i)) * q_hat + co(k_.hcphi1c(i)) * p_hat;
  for (int j = 0; j + 1 < i; ++j) s.r_hat -= co(k_.abar(i, j)) * stored_force(G(j));
  if (i == 0 && carried_for_ == at_->step) {  // (formed by the step before: carry)
    s.Q_hat = next_Q0_;
    return;
  }
  if (i == 0) {  // (the newest node is the step before's: long known)
    Work guess;
    predictor_.predict(i, guess);
    s.Q_hat = first_iterate(s.r_hat, s.abar_ii, guess);
    return;
  }
  Work rest;
  const double w0 = predictor_.predict_rest(i, rest, predictor_.stored());
  const auto g = stored_force(G(i - 1));
  const auto abar_newest = co(k_.abar(i, i - 1));
  s.Q_hat = (s.r_hat - s.abar_ii * rest) - (abar_newest + s.abar_ii * w0) * g;
  s.r_hat -= abar_newest * g;
}

// With a fixed D, at the end of a step (before advance) whose new state is (q_part, p_part)
// without the last stage's terms, -h^2 bbar_last G_last and -h b_last G_last: the next step's Q_0
// of stage 0, one multiply-subtract after this step's last force G_last, as start_fixed forms Q_0
// after G_{i-1}: Q_0 = phi0c_0 q_new + hcphi1c_0 p_new - h^2 abar_00 (rest + w_0 G_last), rest the
// guess's other nodes, = (phi0c_0 q_part + hcphi1c_0 p_part - h^2 abar_00 rest) - (phi0c_0 h^2
// bbar_last + hcphi1c_0 h b_last + h^2 abar_00 w_0) G_last. (A guess: q_new without the
// compensated summation's error. Formed only with the history full, when advance changes no
// weight, and for an implicit stage 0. Without it, the chain from G_last through the update, the
// state's stores and r_0 to Q_0 was on the path of the next step's first gradient evaluation.)
template <class Space, class Coef>
template <class X, class B>
[[gnu::always_inline]] inline void StageSolver<Space, Coef>::carry(int last, const X& q_part,
                                                                   const X& p_part,
                                                                   const B& h2bbar_last,
                                                                   const B& hb_last) {
  if constexpr (Space::kFixed) {
    if (record_[0].explicit_stage || !predictor_.full_history()) return;
    const auto co = [](const auto& value) { return Space::co(value); };
    const auto phi0c = co(k_.phi0c(0)), hcphi1c = co(k_.hcphi1c(0)), abar = co(k_.abar(0, 0));
    Work rest;
    const double w0 = predictor_.predict_rest(0, rest, predictor_.next());
    const auto g = stored_force(G(last));
    next_Q0_ = (phi0c * q_part + hcphi1c * p_part - abar * rest) -
               (phi0c * h2bbar_last + hcphi1c * hb_last + abar * w0) * g;
    carried_for_ = at_->step + 1;
  }
}

}  // namespace erkn::detail

#include "stage_fixed_point.hpp"
#include "stage_newton.hpp"
