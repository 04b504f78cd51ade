// The step of eq. (d) for methods with implicit stages in one process: the stage solver
// (stage_solver.hpp) over the serial space of M's eigenbasis (serial_space.hpp), composed with
// the method's coefficients. D: the dimension when it is a compile-time constant (tiny systems
// with M's identity eigenbasis). Explicit methods step in explicit_stepper.hpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

#include "block_pool.hpp"
#include "erkn/integrator.hpp"
#include "implicit_passes.hpp"
#include "serial_space.hpp"
#include "stage_checks.hpp"
#include "stage_solver.hpp"
#include "step_coefficients.hpp"
#include "stepper_base.hpp"

namespace erkn::detail {

template <class Transform, class Coef, int D = Eigen::Dynamic>
class Stepper final : public StepperBase {
  using Space = SerialSpace<Transform, D>;
  using Map = typename Space::Map;
  // The coefficients' type: with a fixed D an array of D values (a diagonal M;
  // step_coefficients.hpp keeps them inside the stepper, each slot D apart), else Coef.
  using K = std::conditional_t<D != Eigen::Dynamic && !std::is_same_v<Coef, double>,
                               Eigen::Array<double, D, 1>, Coef>;

 public:
  /// lambda: M's eigenvalues ({0} for RKN methods, whose force then includes -M q).
  Stepper(const Method& method, System system, double h, const Options& options,
          Transform transform, const Eigen::VectorXd& lambda, Eigen::Index d)
      : method_(method),
        s_(method.stages()),
        system_(std::move(system)),
        options_(options),
        k_(method, h, lambda),
        place_{&method_},
        space_(std::move(transform), system_.M, d, method.kind() == Kind::rkn),
        block_(space_.template block<6>(6)),
        views_(views()),
        solver_(method_, system_, options_, space_, k_) {}

  Stepper(const Stepper&) = delete;  // (the maps view its own buffers)
  Stepper& operator=(const Stepper&) = delete;

  // Its storage: the block this thread's last implicit stepper of its size gave back
  // (block_pool.hpp: ~10.8 KB at D = 2, above glibc's per-thread cache; malloc and free were
  // ~16 % of the time of a construct + 1-step run of SERKN2s3 at P3, perf).
  static void* operator new(std::size_t bytes) {
    static_assert(alignof(Stepper) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__, "malloc's alignment");
    return take_kept_block(bytes);
  }
  static void operator delete(void* block, std::size_t bytes) noexcept {
    give_kept_block(block, bytes);
  }

  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p, Statistics&) override {
    space_.forward(q, q_hat());
    space_.forward(p, p_hat());
    eq_hat().setZero();
    ep_hat().setZero();
    solver_.reset();
  }

  void get_state(Eigen::VectorXd& q, Eigen::VectorXd& p, Statistics&) override {
    space_.inverse(q_hat(), q);
    space_.inverse(p_hat(), p);
  }

  void step(long step_number, double t, Statistics& stats) override {
    advance<0>(step_number, t, stats);
  }

  // With a fixed D, the loop over the inlined step (a virtual call per step and its frame were 22
  // of the 652 instructions per step of P2 with SERKN1s2(1), construction included; callgrind);
  // with a dynamic D, a direct call of step() (the step inlined into both grew integrator.cpp
  // until GCC left Eigen's loops in the dynamic fixed_point out of line: sine-Gordon N = 32, RKN
  // methods +1.8 % instructions per grad U).
  void steps(long n, long first, const TimeGrid& grid, Statistics& stats, long& done) override {
    if constexpr (Space::kFixed) {
      switch (s_) {
        case 1:
          return fixed_steps<1>(n, first, grid, stats, done);
        case 2:
          return fixed_steps<2>(n, first, grid, stats, done);
        case 3:
          return fixed_steps<3>(n, first, grid, stats, done);
        case 4:
          return fixed_steps<4>(n, first, grid, stats, done);
        default:
          return fixed_steps<0>(n, first, grid, stats, done);
      }
    }
    for (done = 0; done < n; ++done) step(first + done, grid.ahead(done), stats);
  }

  void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) override { space_.apply_M(x, y); }
  System& system() override { return system_; }

 private:
  // steps() with a fixed D: the stage count S = s_ a compile-time constant for up to 4 stages
  // (every implicit method of the registry; more: S = 0, a loop over s_ stages). Each stage is
  // then inlined on its own (StageSolver::for_each_stage), its coefficients (with
  // StepCoefficients::layout_s), records and arrays at constant offsets, no stage loop. P3,
  // SERKN2s3, callgrind: 570 -> 486 instructions per step in Stepper::steps (the layout alone:
  // 606 -> 570; the state's views and the predictor's advance with S: -> 455). integrator.cpp's
  // code grows by ~0.5 MB (1.5 -> 2.0 MB text).
  template <int S>
  void fixed_steps(long n, long first, const TimeGrid& grid, Statistics& stats, long& done) {
    for (done = 0; done < n; ++done) advance<S>(first + done, grid.ahead(done), stats);
  }

  // One step, counted into stats once it has succeeded (a failed step counts nothing). S: the
  // stage count when known at compile time, else 0.
  template <int S>
  [[gnu::always_inline]] void advance(long step_number, double t, Statistics& stats) {
    place_.step = step_number;
    place_.t = t;
    long evaluations;
    if constexpr (Space::kFixed)
      evaluations = solver_.template solve_inline<S>(q_hat(), p_hat(), place_);
    else
      evaluations = solver_.solve(q_hat(), p_hat(), place_);
    update<S>(place_);
    solver_.count(evaluations, stats);
    solver_.template advance<S>();
    ++stats.steps;
  }

  // Eq. (d)'s update from the solved stages (implicit_passes.hpp), added to the state only at the
  // end: with a fixed D on whole arrays the compiler keeps in registers (compute_into,
  // stage_predictor.hpp), else in passes over the arrays of eigen coordinates.
  template <int S>
  [[gnu::always_inline]] void update(const StepPlace& at) {
    if constexpr (Map::RowsAtCompileTime == Eigen::Dynamic) {
      update_arrays(at);
    } else {
      typename Map::PlainObject dq, dp;
      update_values<S>(dq, dp, at);
    }
  }
  // (Both updates and the add always inlined into step: in a call of their own the increments
  // went through memory, P3: 4-5 % more instructions per grad U.)
  template <int S, class Increment>
  [[gnu::always_inline]] void update_values(Increment& dq, Increment& dp, const StepPlace& at) {
    const auto co = [](const auto& value) { return Space::co(value); };
    const StepCoefficients<K>& k = k_;
    const int s = S > 0 ? S : s_;
    update_start(co(k.phi0m1()), co(k.hphi1()), co(k.mhMphi1()), q_hat(), p_hat(), dq, dp);
    for (int i = 0; i + 1 < s; ++i)
      update_stage(co(k.h2bbar(i)), co(k.hb(i)), stored_force(solver_.G(i)), dq, dp);
    const int last = s - 1;  // (the next step's first guess formed before its terms: carry)
    solver_.carry(last, q_hat() + dq, p_hat() + dp, co(k.h2bbar(last)), co(k.hb(last)));
    update_stage(co(k.h2bbar(last)), co(k.hb(last)), stored_force(solver_.G(last)), dq, dp);
    require_finite_result((q_hat() + dq).eval(), (p_hat() + dp).eval(), at);
    add_values(dq, dp);
  }
  // The passes: dq, dp with the non-finite bits of the result, then the adds.
  void update_arrays(const StepPlace& at) {
    constexpr int kLanes = int(sizeof(typename Space::Scalar) / sizeof(double));
    const StepCoefficients<K>& k = k_;
    const UpdateCoefficients<C> c{coefficient(k.phi0m1()), coefficient(k.hphi1()),
                                  coefficient(k.mhMphi1())};
    const UpdateBits bits = update_passes<kLanes>(
        s_, space_.size(), lanes(q_hat()), lanes(p_hat()), lanes(dq_hat()), lanes(dp_hat()), c,
        [&](int i) {
          return std::tuple{lanes(solver_.G(i)), coefficient(k.h2bbar(i)), coefficient(k.hb(i))};
        });
    if (bits.q || bits.p) non_finite_result(bits.q == 0, at);
    const auto add_pass_of = [&](Map& x, Map& error, Map& dx) {
      if (options_.compensated_summation)
        add_pass<kLanes, true>(space_.size(), lanes(x), lanes(error), lanes(dx));
      else
        add_pass<kLanes, false>(space_.size(), lanes(x), lanes(error), lanes(dx));
    };
    add_pass_of(q_hat(), eq_hat(), dq_hat());
    add_pass_of(p_hat(), ep_hat(), dp_hat());
  }
  // The passes' view of an array (as doubles) and of a coefficient (a number, or its values).
  using C = std::conditional_t<std::is_same_v<K, double>, double, const double*>;
  static double* lanes(Map x) { return reinterpret_cast<double*>(x.data()); }
  template <class V>
  static C coefficient(const V& value) {
    if constexpr (std::is_same_v<C, double>)
      return value;
    else
      return value.data();
  }

  // q += dq, p += dp in eigen coordinates, Kahan-compensated when enabled (compensated_sum.hpp;
  // with a fixed D on values the compiler keeps in registers: through the maps each of its sums
  // was stored and reloaded). (The option tested once: tested per array, GCC reloaded and tested
  // it twice.)
  template <class Increment>
  [[gnu::always_inline]] void add_values(Increment& dq, Increment& dp) {
    if (!options_.compensated_summation) {
      q_hat() += dq;
      p_hat() += dp;
    } else {
      compensated_add_values(q_hat(), eq_hat(), dq);
      compensated_add_values(p_hat(), ep_hat(), dp);
    }
  }
  template <class Increment>
  [[gnu::always_inline]] static void compensated_add_values(Map x, Map error, Increment& dx) {
    typename Map::PlainObject x_value = x, error_value = error;
    compensated_add(x_value, error_value, dx);
    x = x_value, error = error_value;
  }

  Method method_;
  int s_;  // stages
  System system_;
  Options options_;
  StepCoefficients<K> k_;
  StepPlace place_;  // the step being taken (for messages)
  Space space_;
  // The state (q, p) in eigen coordinates, its summation errors, the increments of a step, and
  // their views: with a fixed D formed where used, at constant offsets from the stepper (kept as
  // members, their pointers were loaded at each use: ~10 instructions per step at P3), else kept
  // (formed at each use, SerialSpace::map's loads: sine-Gordon N = 32, +24 per step).
  alignas(EIGEN_MAX_ALIGN_BYTES) typename Space::template Block<6> block_;
  using Views = std::conditional_t<Space::kFixed, std::tuple<>, std::array<Map, 6>>;
  [[no_unique_address]] Views views_;
  Views views() {
    if constexpr (Space::kFixed)
      return {};
    else
      return {space_.map(block_, 0), space_.map(block_, 1), space_.map(block_, 2),
              space_.map(block_, 3), space_.map(block_, 4), space_.map(block_, 5)};
  }
  decltype(auto) array(int k) {
    if constexpr (Space::kFixed)
      return space_.map(block_, k);
    else
      return (views_[size_t(k)]);
  }
  decltype(auto) q_hat() { return array(0); }
  decltype(auto) p_hat() { return array(1); }
  decltype(auto) eq_hat() { return array(2); }
  decltype(auto) ep_hat() { return array(3); }
  decltype(auto) dq_hat() { return array(4); }
  decltype(auto) dp_hat() { return array(5); }
  StageSolver<Space, K> solver_;
};

}  // namespace erkn::detail
