// The step of eq. (d) for methods with implicit stages in one process: the stage solver
// (stage_solver.hpp) over the serial space of M's eigenbasis (serial_space.hpp), composed with
// the method's coefficients. D: the dimension when it is a compile-time constant (tiny systems
// with M's identity eigenbasis). Explicit methods step in explicit_stepper.hpp.
#pragma once

#include <Eigen/Core>
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
        q_hat_(space_.map(block_, 0)),
        p_hat_(space_.map(block_, 1)),
        eq_hat_(space_.map(block_, 2)),
        ep_hat_(space_.map(block_, 3)),
        dq_hat_(space_.map(block_, 4)),
        dp_hat_(space_.map(block_, 5)),
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
    space_.forward(q, q_hat_);
    space_.forward(p, p_hat_);
    eq_hat_.setZero();
    ep_hat_.setZero();
    solver_.reset();
  }

  void get_state(Eigen::VectorXd& q, Eigen::VectorXd& p, Statistics&) override {
    space_.inverse(q_hat_, q);
    space_.inverse(p_hat_, p);
  }

  void step(long step_number, double t, Statistics& stats) override {
    advance(step_number, t, stats);
  }

  // With a fixed D, the loop over the inlined step (a virtual call per step and its frame were 22
  // of the 652 instructions per step of P2 with SERKN1s2(1), construction included; callgrind);
  // with a dynamic D, a direct call of step() (the step inlined into both grew integrator.cpp
  // until GCC left Eigen's loops in the dynamic fixed_point out of line: sine-Gordon N = 32, RKN
  // methods +1.8 % instructions per grad U).
  void steps(long n, long first, const TimeGrid& grid, Statistics& stats, long& done) override {
    for (done = 0; done < n; ++done) {
      if constexpr (Space::kFixed)
        advance(first + done, grid.ahead(done), stats);
      else
        step(first + done, grid.ahead(done), stats);
    }
  }

  void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) override { space_.apply_M(x, y); }
  System& system() override { return system_; }

 private:
  // One step, counted into stats once it has succeeded (a failed step counts nothing).
  [[gnu::always_inline]] void advance(long step_number, double t, Statistics& stats) {
    place_.step = step_number;
    place_.t = t;
    long evaluations;
    if constexpr (Space::kFixed)
      evaluations = solver_.solve_inline(q_hat_, p_hat_, place_);
    else
      evaluations = solver_.solve(q_hat_, p_hat_, place_);
    update(place_);
    solver_.count(evaluations, stats);
    solver_.advance();
    ++stats.steps;
  }

  // Eq. (d)'s update from the solved stages (implicit_passes.hpp), added to the state only at the
  // end: with a fixed D on whole arrays the compiler keeps in registers (compute_into,
  // stage_predictor.hpp), else in passes over the arrays of eigen coordinates.
  [[gnu::always_inline]] void update(const StepPlace& at) {
    if constexpr (Map::RowsAtCompileTime == Eigen::Dynamic) {
      update_arrays(at);
    } else {
      typename Map::PlainObject dq, dp;
      update_values(dq, dp, at);
    }
  }
  // (Both updates and the add always inlined into step: in a call of their own the increments
  // went through memory, P3: 4-5 % more instructions per grad U.)
  template <class Increment>
  [[gnu::always_inline]] void update_values(Increment& dq, Increment& dp, const StepPlace& at) {
    const auto co = [](const auto& value) { return Space::co(value); };
    const StepCoefficients<K>& k = k_;
    update_start(co(k.phi0m1()), co(k.hphi1()), co(k.mhMphi1()), q_hat_, p_hat_, dq, dp);
    for (int i = 0; i + 1 < s_; ++i)
      update_stage(co(k.h2bbar(i)), co(k.hb(i)), stored_force(solver_.G(i)), dq, dp);
    const int last = s_ - 1;  // (the next step's first guess formed before its terms: carry)
    solver_.carry(q_hat_ + dq, p_hat_ + dp, co(k.h2bbar(last)), co(k.hb(last)));
    update_stage(co(k.h2bbar(last)), co(k.hb(last)), stored_force(solver_.G(last)), dq, dp);
    require_finite_result((q_hat_ + dq).eval(), (p_hat_ + dp).eval(), at);
    add_values(dq, dp);
  }
  // The passes: dq_hat_, dp_hat_ with the non-finite bits of the result, then the adds.
  void update_arrays(const StepPlace& at) {
    constexpr int kLanes = int(sizeof(typename Space::Scalar) / sizeof(double));
    const StepCoefficients<K>& k = k_;
    const UpdateCoefficients<C> c{coefficient(k.phi0m1()), coefficient(k.hphi1()),
                                  coefficient(k.mhMphi1())};
    const UpdateBits bits = update_passes<kLanes>(
        s_, space_.size(), lanes(q_hat_), lanes(p_hat_), lanes(dq_hat_), lanes(dp_hat_), c,
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
    add_pass_of(q_hat_, eq_hat_, dq_hat_);
    add_pass_of(p_hat_, ep_hat_, dp_hat_);
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
      q_hat_ += dq;
      p_hat_ += dp;
    } else {
      compensated_add_values(q_hat_, eq_hat_, dq);
      compensated_add_values(p_hat_, ep_hat_, dp);
    }
  }
  template <class Increment>
  [[gnu::always_inline]] static void compensated_add_values(Map& x, Map& error, Increment& dx) {
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
  // The state (q, p) in eigen coordinates, its summation errors, the increments of a step.
  alignas(EIGEN_MAX_ALIGN_BYTES) typename Space::template Block<6> block_;
  Map q_hat_, p_hat_, eq_hat_, ep_hat_, dq_hat_, dp_hat_;
  StageSolver<Space, K> solver_;
};

}  // namespace erkn::detail
