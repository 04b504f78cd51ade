// The step of an explicit method (every abar_ii identically 0), generic over M's eigenbasis
// (Transform) and the coefficient type (Coef). Such a method is a splitting (docs/design.md §1,
// the explicit family) and steps as one: exact flows of q'' + M q = 0 over tau_k =
// h (c_k - c_{k-1}) (c_0 = 0 before the first node, c_{s+1} = 1 after the last) alternated with
// kicks p -= h d_k g_k, g_k = grad U(Q_k) (+ M Q_k for RKN methods), passes over the eigen
// coordinates (explicit_passes.hpp: a kick and the flow after it make one pass); a modified kick
// (modified_force.hpp) kicks by h with the stage force d_k g_k + h^2 e_k G(Q_k). With c_1 = 0 and
// c_s = 1 the first kick reuses the previous step's last force (FSAL) when the two kicks mix g and
// G alike. The first pass reads the state and writes a second copy of it, which replaces the state
// once every gradient has been evaluated and the result is finite: a failed step leaves the state
// unchanged. Over arrays that outgrow the caches a step of one pass overwrites its start instead
// where it cannot fail: from a state and with a force bounded so that every value it makes is
// finite (in_place_steps; explicit_passes.hpp, kPBound).
//
// A processed method (Method::is_processed, processor.hpp) steps its kernel K: set_state applies
// pi^-1 to the user's state and get_state pi to a copy of the kernel's, each counted in the
// statistics (Statistics::processor_applications, and their gradients).
//
// The last flow of a step and the first of the next are one exact flow (over tau_s + tau_0). Over
// arrays a step's last pass kicks and makes that flow, staging the next step's first Q, so the
// stored state runs one flow ahead: after a step it is the state after flow 0 of the next
// (ahead_), whose first gradient needs no pass before it: a step of s stages makes s passes where
// the specialist's loop makes s + 1 (with the passes' checks cut to one value per coordinate,
// explicit_passes.hpp: erkn_integrate_benchmark --short, runs alternated with main 724a43f,
// medians of 6-10, gradient compiled in, compensation off, Strang against the specialist's loop,
// sine-Gordon N = 32 1.040 -> 1.000, 512 1.026 -> 0.988, 2048 1.007 -> 0.938, 8192 1.005 ->
// 0.959; SABA2 N = 512 1.003 -> 0.961; Intel Xeon under KVM). get_state applies flow 0
// backwards (over -tau_0) to a copy. When D, the dimension, is a
// compile-time constant (tiny systems with M's identity eigenbasis: the state in registers, no
// pass to save) the stored state stays one flow behind: after a step it is the state before flow
// s, which is pending (pending_); the next step starts with the merged flow, and get_state
// applies flow s to a copy. Either way the state returned is the one the unmerged steps give, up
// to round-off.
//
// The gradient is the policy Gradient's: System::gradient, a std::function on Eigen::VectorXd
// (SystemGradient), or a functor compiled into the step (CompiledGradient,
// erkn/compiled_gradient.hpp): with a fixed D on fixed-size vectors, so that the values of a
// stage stay in registers across the call (through a std::function every double live across it
// is spilled: on x86-64 the vector registers are caller-saved); in a half-spectrum basis on the
// stepper's vectors, its loop inlined where the specialist's is (through System::gradient,
// sine-Gordon N = 32 costs 5-10 % more, and so does the specialist's loop through it). The
// arithmetic is the same on both: the same step, the same checks and messages. A functor with a
// Hessian-vector product as well (CompiledGradient::kProduct) has modified kicks call it on the
// same vectors; otherwise System's other callbacks (the Hessians of modified kicks) and M Q (RKN
// methods) take exact copies of the fixed-size Q and g as Eigen::VectorXd.
//
// The transform may also be a space of several processes (mpi/src/slab_space.hpp: a grid or
// circulant M distributed over MPI ranks, whose transforms are collective). Such a space defers
// the step's checks (kDeferred): its gradient keeps a failure (g zeroed) instead of throwing, as
// do the checks of the passes (fail), and settle() at the end of the step, one reduce over every
// process, throws the first failure on all of them alike before the state is replaced; a process
// that threw alone would leave the others waiting in a transform. Its force in eigen coordinates
// is the space's to_eigen_force (M Q added there for RKN methods), and so is apply_M.
//
// Compensated summation (Options::compensated_summation) keeps with q and p the low-order parts
// eq, ep that rounding has dropped; get_state returns q + eq and p + ep. With arrays it works in
// increment form (explicit_passes.hpp): a step's passes accumulate its increments of q and p from
// the state at its start in plain arithmetic, and one compensated sum per step adds them to the
// state (q's in the step's last flow, p's in its last kick). Compensating every pass's sums, as
// before, had every pass read and write eq and ep as well.
//
// Its cost (construction + integrate; scripts/main.sh's two runs of erkn_integrate_benchmark
// --short on main 19bad58, quiet machine, docs/benchmarks.md: each method's defaults ratio over
// its compensation-off ratio against the same peer, median and range over the 14 explicit
// methods and both runs, through System::gradient | the gradient compiled in): sine-Gordon
// N = 512 1.036x (1.030-1.046) | 1.039x (1.014-1.047), N = 2048 1.034x | 1.034x, N = 8192
// 1.036x | 1.040x, 256^2 1.046x (1.032-1.180) | 1.050x (1.036-1.100); N = 32 1.024x | 1.035x;
// Duffing and stellar orbits (a fixed dimension) 0.99-1.02x. At N >= 512 it costs time through
// memory more than instructions (callgrind, N = 512, SABA2: 1.014x the instructions since the
// AVX entry of c55998a; its L1 misses: the passes' working set outgrows L1 with eq, ep).
// What it leaves (against a long-double run of the same map with the runtime's coefficients;
// harmonic oscillators d = 8: SABA2, Yoshida4, ABA864, SRKN14a; sine-Gordon N = 32: SABA2,
// ABA864; N = 512: SABA2; 1e3 to 1e6 steps): errors of q and of the energy 1.5-5 orders below
// the plain path's at every step count, as before; both compensations leave the rounding of the
// increments themselves (~sqrt(n) eps h |w p|), in increment form 0.015-12x the previous one's
// (e.g. 1e6 steps of the 14-stage SRKN14a, |q - q_ref| 2.2e-14 against 4.5e-15, plain 1.9e-10;
// sine-Gordon N = 32 is chaotic: after 1e4 steps every run has left the reference).
// That is within the 5 % the runtime allows itself for a default at N >= 512 by the median and
// at its edge on the 256^2 grid (single cells up to 1.18x in one of the two runs). On an Intel
// Xeon host (main a5670a2, the same two runs, gradient compiled in) N = 512-8192 read
// 1.036-1.045x by the median, and the 256^2 grid 1.107x (1.081-1.140), where the state's four
// arrays and the second copy's outgrow the caches (a step of one pass there is in place:
// in_place_steps). It stays the default: without it the round-off of q_n + dq grows with the
// number of steps (a random walk, ~sqrt(n) eps |q|), which is what the energy and long-time
// charts show and what the paper's claims rest on; Options::compensated_summation = false is the
// fast path.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "block_pool.hpp"
#include "erkn/error.hpp"
#include "erkn/integrator.hpp"
#include "explicit_passes.hpp"
#include "flow_coefficients.hpp"
#include "m_operator.hpp"
#include "modified_force.hpp"
#include "processor.hpp"
#include "stage_checks.hpp"
#include "stepper_base.hpp"

namespace erkn::detail {

/// The gradient through System::gradient (on Eigen::VectorXd); modified kicks call System's
/// Hessian (-vector product) too.
struct SystemGradient {
  using Vector = Eigen::VectorXd;
  static constexpr bool kProduct = false;
  void operator()(const System& system, const Vector& q, Vector& g) const { system.gradient(q, g); }
};
/// The gradient G compiled into the step: g(q, out) on fixed-size vectors of dimension D, or
/// (D = Eigen::Dynamic) on maps of the stepper's Eigen::VectorXd (g sized, not to be resized).
/// When G also has hessian_vector(q, v, out) (out = Hess U(q) v, on the same vectors: kProduct),
/// modified kicks call that in place of System's Hessian-vector product.
template <class G, int D>
struct CompiledGradient {
  using Vector = std::conditional_t<D == Eigen::Dynamic, Eigen::VectorXd,
                                    Eigen::Matrix<double, D, 1, Eigen::DontAlign>>;  // (Physical)
  // What G is called on: the vectors themselves, or maps of them.
  using In = std::conditional_t<D == Eigen::Dynamic, Eigen::Map<const Eigen::VectorXd>, Vector>;
  using Out = std::conditional_t<D == Eigen::Dynamic, Eigen::Map<Eigen::VectorXd>, Vector>;
  static constexpr bool kProduct = requires(const G& f, const In& x, Out& y) {
    f.hessian_vector(x, x, y);
  };

  void operator()(const System&, const Vector& q, Vector& g) const {
    if constexpr (D == Eigen::Dynamic) {
      Out out(g.data(), g.size());
      gradient(In(q.data(), q.size()), out);
    } else {
      gradient(q, g);
    }
  }
  /// hv = Hess U(q) v through G (kProduct only).
  void product(const Vector& q, const Vector& v, Vector& hv) const {
    if constexpr (D == Eigen::Dynamic) {
      Out out(hv.data(), hv.size());
      gradient.hessian_vector(In(q.data(), q.size()), In(v.data(), v.size()), out);
    } else {
      gradient.hessian_vector(q, v, hv);
    }
  }
  G gradient;
};

template <class Transform, class Coef, int D = Eigen::Dynamic, class Gradient = SystemGradient>
class ExplicitStepper final : public StepperBase {
  using Spectral = typename Transform::Spectral;
  using Scalar = typename Spectral::Scalar;
  static constexpr bool kFixed = D != Eigen::Dynamic;
  // (Aligned when Arrays::stride keeps the arrays aligned: in the dynamic-size storage.)
  static constexpr int kAlignment = kFixed ? Eigen::Unaligned : Eigen::AlignedMax;
  using SpectralMap = Eigen::Map<Spectral, kAlignment>;
  using ConstMap = Eigen::Map<const Spectral, kAlignment>;
  static constexpr bool kIdentity = std::is_same_v<Transform, IdentityTransform>;
  // A transform with a staging buffer (HalfSpectrumTransform): the flow before a gradient writes
  // the stage's eigen coordinates there, scaled, and the inverse transform needs no copy pass.
  static constexpr bool kStaged = requires(Transform & t) { t.staging(); };
  // One that also inverts y scaled as staged from an array of the caller's (get_state's p).
  static constexpr bool kScaledInverse = requires(Transform & t, Scalar* y, Eigen::VectorXd& x) {
    t.inverse_scaled(y, x);
  };
  // A space of several processes, whose checks are collective (see above).
  static constexpr bool kDeferred = requires(Transform & t, const Error& e) { t.defer(e); };
  static_assert(!kFixed || kIdentity, "a fixed dimension needs the identity basis");
  // The state (q, p, eq, ep), the gradient of the current stage and the last stage's gradient of
  // the previous step; with a dynamic dimension also the state's second copy (4 arrays).
  static constexpr int kArrays = kFixed ? 6 : 10;
  // Their storage: one block, kept for the process's next stepper when large (block_pool.hpp),
  // or (fixed dimension) inside the stepper.
  using Storage =
      std::conditional_t<kFixed, std::array<Scalar, kArrays * std::max(D, 1)>, PooledArray<Scalar>>;

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
  // The kArrays arrays in eigen coordinates, m entries each and stride apart, in one allocation
  // (a fixed dimension: inside the stepper; uninitialised with a dynamic dimension: set_state
  // writes the state, every pass what it reads later), and the views a step swaps.
  struct Arrays {
    explicit Arrays(Eigen::Index m)
        : m(m),
          stride(kFixed ? D : aligned_stride<Scalar>(m)),
          storage(allocate(stride)),
          state{slot(0), slot(1), slot(2), slot(3)},
          G(slot(4)),
          G_last(slot(5)),
          work{slot(6), slot(7), slot(8), slot(9)} {}
    Arrays(const Arrays&) = delete;  // (the views point into storage)
    Arrays& operator=(const Arrays&) = delete;
    static Storage allocate(Eigen::Index stride) {
      if constexpr (kFixed)
        return Storage{};
      else
        return Storage(kArrays * stride);
    }
    // Slot k (the second copy's slots 6..9 exist with a dynamic dimension only).
    Scalar* slot(int k) { return k < kArrays ? storage.data() + k * stride : nullptr; }
    Eigen::Index m, stride;
    Storage storage;
    State state;         // q, p, eq, ep
    Scalar *G, *G_last;  // the current stage's force; the last stage's of the previous step
    State work;          // the state's second copy (dynamic dimension only)
  };
  // Physical coordinates: the stage Q and its gradient g (the gradient's arguments), M Q for RKN
  // methods, and (fixed-size Q and g, callbacks besides the gradient: RKN, modified kicks without
  // a compiled product) their copies as Eigen::VectorXd, in a block of their own. (With the copies
  // inside and Q, g aligned to 16 bytes the stepper of d = 4 with an 8-byte functor took 1056
  // bytes, beyond the 1032 glibc's per-thread cache serves, allocation_test.cpp; now 1032.)
  using Vector = typename Gradient::Vector;
  static constexpr bool kDynamicVector = std::is_same_v<Vector, Eigen::VectorXd>;
  struct Copies {
    explicit Copies(Eigen::Index d) : Q(d), g(d) {}
    Eigen::VectorXd Q, g;
  };
  struct NoCopies {};  // (SystemGradient: no member, so the stepper stays as small)
  static auto copies(Eigen::Index d, bool callbacks) {
    if constexpr (kDynamicVector)
      return NoCopies{};
    else
      return callbacks ? std::make_unique<Copies>(d) : nullptr;
  }
  // (Q and g of a dynamic dimension uninitialised: the flow or the transform writes Q, the
  // gradient g, before either is read; zeroing them was ~2.5 us of a construction at N = 8192.)
  static Vector sized(Eigen::Index d) {
    if constexpr (kDynamicVector)
      return Vector(d);
    else
      return Vector::Zero(d);
  }
  struct Physical {
    Physical(Eigen::Index d, bool rkn, bool callbacks)
        : Q(sized(d)), g(sized(d)), Mq(rkn ? d : 0), x(copies(d, callbacks)) {}
    Vector Q, g;
    Eigen::VectorXd Mq;
    [[no_unique_address]] decltype(copies(0, false)) x;
  };
  // A processed method's processor (processor.hpp), the state pi or pi^-1 works on, get_state's
  // physical copy of the kernel's state, and the kernel's saved state (save_kernel: the state
  // arrays, the last stage's force, have_history_, pending_). Other methods have none: the
  // stepper of a small dimension stays a block glibc's per-thread cache serves,
  // allocation_test.cpp.
  struct Processing {
    Processing(const Method& method, double h, const Eigen::VectorXd& lambda, Eigen::Index m,
               Eigen::Index d)
        : coefficients(method, h, lambda), q(m), p(m), kernel_q(d), kernel_p(d), saved(5 * m) {}
    ProcessorCoefficients coefficients;
    Spectral q, p;
    Eigen::VectorXd kernel_q, kernel_p;
    Spectral saved;  // q, p, eq, ep, G_last, m entries each
    bool history = false, pending = false, ahead = false;
  };

 public:
  /// lambda: M's eigenvalue of each eigen coordinate ({0} for RKN methods, whose force then
  /// includes M q).
  ExplicitStepper(const Method& method, System&& system, double h, const Options& options,
                  Transform transform, const Eigen::VectorXd& lambda, Eigen::Index d,
                  Gradient gradient = Gradient())
      : method_(method),
        system_(std::move(system)),
        kahan_(options.compensated_summation),
        rkn_(method.kind() == Kind::rkn),
        kicks_(method, h),
        flows_(method, h, lambda, options.compensated_summation),
        transform_(std::move(transform)),
        M_(m_operator(system_.M, d)),
        arrays_(transform_.spectral_size(d)),
        physical_(d, rkn_,
                  rkn_ || (!Gradient::kProduct &&
                           (method.has_modified_kicks() || method.is_processed()))),
        gradient_(std::move(gradient)),
        modified_((method.has_modified_kicks() || method.is_processed()) &&
                          !(kFixed && Gradient::kProduct)
                      ? d
                      : 0),  // (a fixed D's compiled product has its Hv on the stack)
        processing_(method.is_processed()
                        ? std::make_unique<Processing>(method, h, lambda, arrays_.m, d)
                        : nullptr) {
    in_place_ = in_place_steps();  // (after every member it reads)
  }

  ExplicitStepper(const ExplicitStepper&) = delete;  // (the pointers view its own buffer)
  ExplicitStepper& operator=(const ExplicitStepper&) = delete;

  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& p, Statistics& stats) override {
    if (method_.is_processed()) {  // (pi^-1 on a copy: a refused state changes nothing)
      Counts counts;
      transform_.forward(q, processing_->q);
      transform_.forward(p, processing_->p);
      process(processing_->q.data(), processing_->p.data(), false, counts);
      map(arrays_.state.q) = processing_->q, map(arrays_.state.p) = processing_->p;
      count(counts, stats);
    } else {
      forward(q, arrays_.state.q);
      forward(p, arrays_.state.p);
    }
    // (The summation errors are read by compensated passes and get_state, by a processed
    // method's save_kernel, and by a fixed dimension's load; a plain run over arrays never reads
    // them, and at 256^2 zeroing them touched 258 fresh pages per construction.)
    if (kahan_ || kFixed || method_.is_processed()) {
      std::fill_n(arrays_.state.eq, n(), Scalar(0));
      std::fill_n(arrays_.state.ep, n(), Scalar(0));
    }
    have_history_ = false;
    pending_ = ahead_ = staged_ahead_ = false;
  }

  // (A processed method's out of line: with it here, a fixed dimension's load saved six registers
  // at each call, ~20 of its ~85 instructions at d = 1; callgrind, Duffing Strang.)
  void get_state(Eigen::VectorXd& q, Eigen::VectorXd& p, Statistics& stats) override {
    if (method_.is_processed()) [[unlikely]]
      return processed_state(q, p, stats);
    load_state(q, p);
  }

  // (A processed method's only: Integrator::batch.)
  void save_kernel() override {
    Processing& x = *processing_;
    const std::array<Scalar*, 5> kernel = kernel_arrays();
    for (int k = 0; k < 5; ++k) std::copy_n(kernel[k], n(), x.saved.data() + k * arrays_.m);
    x.history = have_history_, x.pending = pending_, x.ahead = ahead_;
  }
  void restore_kernel() override {
    const Processing& x = *processing_;
    const std::array<Scalar*, 5> kernel = kernel_arrays();
    for (int k = 0; k < 5; ++k) std::copy_n(x.saved.data() + k * arrays_.m, n(), kernel[k]);
    have_history_ = x.history, pending_ = x.pending, ahead_ = x.ahead;
    staged_ahead_ = false;
  }

  void step(long step_number, double t, Statistics& stats) override {
    Counts counts;  // (counted into stats once the step has succeeded)
    if (kahan_)
      advance<true>(step_number, t, counts);
    else
      advance<false>(step_number, t, counts);
    count(counts, 1, stats);
  }

  void steps(long n, long first, const TimeGrid& grid, Statistics& stats, long& done) override {
    if (kahan_)
      run<true>(n, first, grid, stats, done);
    else
      run<false>(n, first, grid, stats, done);
  }

  void apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) override {
    // (A space's apply_M transforms back through the staging buffer: the staged Q is lost.)
    if constexpr (kDeferred)
      transform_.apply_M(x, y), staged_ahead_ = false;
    else
      M_->apply(x, y);
  }
  System& system() override { return system_; }

 private:
  struct Counts {
    long gradients = 0, products = 0;  // calls of System::gradient, modified forces formed
    long applications = 0;             // of the processor (pi or pi^-1)
    Counts& operator+=(const Counts& b) {
      gradients += b.gradients, products += b.products, applications += b.applications;
      return *this;
    }
  };

  // get_state of a processed method: pi of the kernel's state (q, p written once pi succeeds).
  [[gnu::noinline]] void processed_state(Eigen::VectorXd& q, Eigen::VectorXd& p,
                                         Statistics& stats) {
    Processing& x = *processing_;
    load_state(x.kernel_q, x.kernel_p);
    Counts counts;  // pi of the kernel's state, in eigen coordinates
    transform_.forward(x.kernel_q, x.q);
    transform_.forward(x.kernel_p, x.p);
    process(x.q.data(), x.p.data(), true, counts);
    transform_.inverse(x.q, q);
    transform_.inverse(x.p, p);
    count(counts, stats);
    staged_ahead_ = false;  // (pi's kicks and the transforms used the staging input)
  }
  // q + eq and p + ep after the pending flow (load), in physical coordinates.
  void load_state(Eigen::VectorXd& q, Eigen::VectorXd& p) {
    if (kahan_)
      load<true>(q, p);
    else
      load<false>(q, p);
  }

  // One step (numbered step_number, from t), its counts added to `counts` as it goes (a step that
  // fails leaves a part of its counts there: step() drops them, run() keeps the counts before it).
  // (Counted in place: a step's own Counts, zeroed and added, were ~12 of the ~38 instructions
  // a step costs outside passes(); callgrind, Duffing Strang.)
  template <bool kKahan>
  EIGEN_ALWAYS_INLINE void advance(long step_number, double t, Counts& counts) {
    place_.step = step_number;
    place_.t = t;
    passes<kKahan>(counts);
    // (FSAL: the last stage's force, for the next step's first kick. Without FSAL nothing reads
    // G_last, and one array takes every force: at 256^2 the other's pages, fresh in every run,
    // were 129 of the ~2500 page faults of a Strang run.)
    if (kicks_.fsal()) std::swap(arrays_.G, arrays_.G_last);
    have_history_ = true;
    pending_ = ends_pending_;
    ahead_ = ends_ahead_;
  }
  // steps(): the completed steps counted into stats once, at the end or at the step that failed.
  template <bool kKahan>
  void run(long n, long first, const TimeGrid& grid, Statistics& stats, long& done) {
    Counts counts, before;  // (before: at the start of the current step)
    long k = 0;
    try {
      for (; k < n; ++k) before = counts, advance<kKahan>(first + k, grid.ahead(k), counts);
    } catch (...) {
      done = k;
      count(before, k, stats);
      throw;
    }
    done = n;
    count(counts, n, stats);
  }

  // The counts of `steps` steps into stats (a step's gradients are its stage iterations).
  void count(const Counts& counts, long steps, Statistics& stats) const {
    stats.steps += steps;
    stats.stage_iterations += counts.gradients;
    count(counts, stats);
  }
  // (The modified kicks' and the processor's counts behind a branch: added with the gradients',
  // the compiler loaded gradients and products as one vector spanning passes()' two scalar
  // stores, which this machine does not store-forward.)
  void count(const Counts& counts, Statistics& stats) const {
    stats.gradient_evaluations += counts.gradients;
    if (counts.products != 0 || counts.applications != 0) count_rare(counts, stats);
  }
  void count_rare(const Counts& counts, Statistics& stats) const {
    stats.hessian_vector_products += counts.products;
    if (!system_.hessian_vector_product) stats.hessian_evaluations += counts.products;
    stats.processor_applications += counts.applications;
  }

  // pi^-1 (backwards = false: the table's pre-sequence drift, kick, ..., drift) or pi (its
  // exact inverse: the same operations reversed, each negated) on eigen coordinates q, p.
  void process(Scalar* q, Scalar* p, bool backwards, Counts& counts) {
    const int m = processing_->coefficients.kicks();
    const double sign = backwards ? -1 : 1;
    place_.processor = backwards ? "pi" : "pi^-1";  // (messages name the processor's kick)
    try {
      for (int j = 0; j <= 2 * m; ++j) {
        const int k = backwards ? 2 * m - j : j;  // (even: drift k/2, odd: kick k/2)
        if (k % 2 == 0)
          processor_drift(processing_->coefficients.drift(k / 2), sign, lanes(q), lanes(p));
        else
          processor_kick(k / 2, sign, q, p, counts);
      }
      // (a finite force can still overflow p, and the last drift then q)
      if (!all_finite(lanes(q), kLanes * n()) || !all_finite(lanes(p), kLanes * n()))
        throw Error(std::string("the processor ") + place_.processor + " of " +
                    std::string(method_.name()) + " (on the state at step " +
                    std::to_string(place_.step) +
                    ") gives a non-finite state; the state is unchanged");
    } catch (...) {
      place_.processor = nullptr;
      throw;
    }
    place_.processor = nullptr;
    ++counts.applications;
  }

  // What the kernel's next steps read and change (with have_history_ and pending_): the state's
  // arrays and the last stage's force, in Processing::saved's order.
  std::array<Scalar*, 5> kernel_arrays() {
    return {arrays_.state.q, arrays_.state.p, arrays_.state.eq, arrays_.state.ep, arrays_.G_last};
  }

  // A state array as its kLanes * n() doubles.
  static double* lanes(Scalar* x) { return reinterpret_cast<double*>(x); }
  static const double* lanes(const Scalar* x) { return reinterpret_cast<const double*>(x); }

  // The exact flow over sign tau of one processor drift (a scalar M: one coefficient for all).
  void processor_drift(const ProcessorCoefficients::Drift& f, double sign, double* q, double* p) {
    const bool one = f.cos.size() == 1;
    for (Eigen::Index e = 0; e < n(); ++e) {
      const Eigen::Index j = one ? 0 : e;
      const double c = f.cos[j], sc = sign * f.sinc[j], ms = sign * f.msinc[j];
      for (int l = 0; l < kLanes; ++l) {
        const Eigen::Index x = kLanes * e + l;
        const double q0 = q[x], p0 = p[x];
        q[x] = c * q0 + sc * p0, p[x] = ms * q0 + c * p0;
      }
    }
  }

  // Processor kick k (sign -1: undone): p -= sign h (y grad U + h^2 v G), or p -= sign h y grad
  // U when v = 0.
  void processor_kick(int k, double sign, const Scalar* q, Scalar* p, Counts& counts) {
    const ProcessorCoefficients::Kick& w = processing_->coefficients.kick(k);
    const bool modified = w.h2v != 0;
    const Scalar* g = force(q, false, false, k, w.y, w.h2v, counts, true);  // (no pass checks it)
    const double weight = sign * kicks_.h() * (modified ? 1.0 : w.y);
    double* pl = lanes(p);
    const double* gl = lanes(g);
    for (Eigen::Index x = 0; x < kLanes * n(); ++x) pl[x] -= weight * gl[x];
  }

  // One step into the second copy (a fixed dimension: whole arrays, which the compiler keeps
  // in registers), checked, and then the state (without summation errors when !kKahan: they then
  // stay zero).
  //
  // With arrays the finiteness checks ride on the passes, which OR the bits of x - x (0 exactly
  // when x is finite; nonfinite_bits) over one check value per coordinate (explicit_passes.hpp,
  // pass): a reduction that vectorises with the pass, where a separate check would reread the
  // arrays, and a test that needs no exact answer: where it fails, a scan of the arrays gives the
  // answer and the message. The force is non-finite when the gradient is (a transform spreads a
  // non-finite entry over all of its outputs), and so is the Q staged after its kick. A Q a flow
  // stages is checked on the way, as below kStageBound (explicit_passes.hpp), and scanned only
  // when it is not (callgrind, sine-Gordon N = 32: the scan was 2.8 % of a plain run); every other
  // stage's physical Q before the gradient is called. The step's last pass checks the p it writes,
  // and the q of its flow (ahead) with them; without that flow q is the last stage's. A fixed
  // dimension checks the same: every stage's Q and g (checked_gradient) and the p of the last kick,
  // its bits taken in registers as that pass makes it. Checking q and p of the step's values after
  // the step instead (reloaded in halves from the stack, where the kick had stored p whole: not
  // forwarded on this AMD EPYC) cost P3 Strang, construct + integrate, ~30 % against the
  // specialist's loop: 1.03 -> 0.77, SABA2 0.81 -> 0.68; taking the bits in every kick as well cost
  // P2 (d = 1, callback) ~12 %.
  template <bool kKahan>
  void passes(Counts& evaluations) {
    if constexpr (kFixed) {
      Values v{Fixed(arrays_.state.q), Fixed(arrays_.state.p), Fixed::Zero(), Fixed::Zero()};
      if (kKahan) v.eq = Fixed(arrays_.state.eq), v.ep = Fixed(arrays_.state.ep);
      bool unused = false;  // (the values are the only copy)
      if (stages<kKahan>(v, v, evaluations, unused)) non_finite_result(true, place_);
      FixedMap(arrays_.state.q) = v.q, FixedMap(arrays_.state.p) = v.p;
      if (kKahan) FixedMap(arrays_.state.eq) = v.eq, FixedMap(arrays_.state.ep) = v.ep;
    } else {
      bool in_place = false;  // (the step overwrote its start: last_pass)
      const bool suspect = stages<kKahan>(arrays_.state, arrays_.work, evaluations, in_place);
      if (suspect) check_result(in_place ? arrays_.state : arrays_.work);
      if constexpr (kDeferred) transform_.settle();  // (every process's checks, before the swap)
      if (!in_place) std::swap(arrays_.state, arrays_.work);
      staged_ahead_ = ends_ahead_ && kStage, bounded_ahead_ = !suspect;
    }
  }
  // The step's result x after its last pass's check failed: q, else p, not finite fails the step
  // (else they are finite, and a staged Q may be large).
  void check_result(const State& x) {
    if (!all_finite(lanes(x.q), kLanes * n()))
      fail([&] { non_finite_result(false, place_); });
    else if (!all_finite(lanes(x.p), kLanes * n()))
      fail([&] { non_finite_result(true, place_); });
  }

  // The flows and kicks from `start` into `to` (S: State or Values; start may be to): arrays from
  // stage 1 when ahead (else flow 0 first), the last kick and the merged flow in one pass; a fixed
  // dimension's first flow merged with the pending one, the last left pending; kick i and flow
  // i + 1 in one pass.
  // In the identity basis each flow before a gradient writes the stage's physical_.Q as it goes
  // (with a staging transform: the inverse transform's input), and the last kick saves the gradient
  // to arrays_.G for FSAL: no pass reloads what the last one stored. Returns whether the last
  // pass's check failed (explicit_passes.hpp, pass); in_place: set where the last pass wrote the
  // start (last_pass).
  template <bool kKahan, class S>
  EIGEN_ALWAYS_INLINE bool stages(const S& start, S& to, Counts& evaluations, bool& in_place) {
    const bool reuse = kicks_.fsal() && have_history_;  // (stage 1's force; its flow never moves)
    const int merged = pending_ ? flows_.merged(method_) : 0;
    bool first = true;     // (no pass made yet: the state is `start`)
    bool folded = false;   // (compensated: q's increments added, after the step's last flow)
    bool staged = false;   // (stage i's Q written by the last pass)
    bool suspect = false;  // (the last pass's check failed)
    if (ahead_) {          // (arrays: stage 1's Q is the state's, staged by the last step)
      staged = staged_ahead_;
      suspect = !bounded_ahead_;
      staged_ahead_ = false;  // (the staging input is this step's from its first gradient on)
    } else if (flows_.moves(merged)) {
      folded = last_flow_ == 0;
      suspect = apply<kKahan, kFlowStaged>(start, to, first, folded, 0, nullptr, merged);
      first = false;
      staged = kStage;
    }
    for (int i = 0; i < kicks_.stages(); ++i) {
      const bool reused = i == 0 && reuse;
      const double hd = kicks_.h() * (reused ? *kicks_.fsal() : kicks_.weight(i));
      // (A staged Q below kStageBound is finite; a fixed dimension's is checked in registers.)
      const bool bounded = !kFixed && staged && !suspect;
      const Scalar* g = reused ? arrays_.G_last
                               : evaluate(stage_q<kKahan>(start, to, first, folded, staged), staged,
                                          bounded, i, evaluations);
      staged = i + 1 < kicks_.stages() && flows_.moves(i + 1);
      if (staged) {
        const bool fold = i + 1 == last_flow_;
        suspect = apply<kKahan, kKickFlow>(start, to, first, fold, hd, g, i + 1);
        folded = folded || fold;
      } else if (i == kicks_.stages() - 1) {
        // (before any pass, ahead and not suspect: the start is bounded, bounded_ahead_)
        const bool bounded_start = first && ahead_ && !suspect;
        suspect = last_pass<kKahan>(start, to, first, folded, hd, g, bounded_start, in_place);
      } else {
        suspect = apply<kKahan, kKick>(start, to, first, false, hd, g, 0);
      }
      staged = staged && kStage;
      // (A failed check: the force, if it is not finite; else what the next stage or the caller
      // scans.)
      if (suspect && !reused && !all_finite(lanes(g), kLanes * n()))
        fail([&] { non_finite_gradient(i, place_); });
      first = false;
    }
    return suspect;
  }
  // The step's last pass: over arrays, when the merged flow moves, the kick and that flow, which
  // stages the next step's first Q (the state is then ahead); else the kick alone (the FSAL
  // force; compensated, p's fold, and q's unless folded).
  // With in_place_ the pass bounds p as well (bound_p: a state with |p| >= kPBound is then
  // scanned after each step), and a step's only pass, from a bounded state (bounded_start) with
  // a bounded force, overwrites the start (in_place_steps), which sets in_place.
  template <bool kKahan, class S>
  EIGEN_ALWAYS_INLINE bool last_pass(const S& start, S& to, bool first, bool folded, double hd,
                                     const Scalar* g, bool bounded_start, bool& in_place) {
    if constexpr (kMayStepInPlace) {
      const int k = flows_.merged(method_);
      if (in_place_) {  // (then ends_ahead_)
        in_place = bounded_start && force_bounded(kLanes * n(), lanes(g), hd);
        if (in_place)
          return apply<kKahan, over_start(kKickFlowLastBounded)>(start, arrays_.state, true, true,
                                                                 hd, g, k);
        return apply<kKahan, kKickFlowLastBounded>(start, to, first, true, hd, g, k);
      }
    }
    if constexpr (!kFixed)
      if (ends_ahead_)
        return apply<kKahan, kKickFlowLast>(start, to, first, true, hd, g, flows_.merged(method_));
    return apply<kKahan, kKickLast>(start, to, first, !folded, hd, g, 0);
  }
  // The stage's q in eigen coordinates where the gradient reads it (not staged, or a deferred
  // space's RKN force): the state's before the step's first pass, else the second copy's, which
  // compensated holds the increment until q is folded: then start.q + dq, summed into its eq
  // (unused until the fold) as a flow stages it.
  template <bool kKahan, class S>
  const Scalar* stage_q(const S& start, S& to, bool first, bool folded, bool staged) {
    if constexpr (std::is_same_v<S, State>) {
      if (first) return start.q;
      if (!kKahan || folded || (staged && !(kDeferred && rkn_))) return to.q;
      const double* __restrict qn = lanes(start.q);
      const double* __restrict dq = lanes(to.q);
      double* __restrict sum = lanes(to.eq);
      for (Eigen::Index j = 0; j < kLanes * n(); ++j) sum[j] = qn[j] + dq[j];
      return to.eq;
    } else {
      return &to.q[0];  // (Values: start is to)
    }
  }

  // get_state: q + eq and p + ep after the pending flow (ahead: flow 0 backwards), rounded (with a
  // dynamic dimension: in the second copy's slots, unused between steps; where they go through the
  // staging buffer, it no longer holds the next step's Q).
  template <bool kKahan>
  void load(Eigen::VectorXd& q, Eigen::VectorXd& p) {
    if constexpr (kFixed) {
      Values v{Fixed(arrays_.state.q), Fixed(arrays_.state.p), Fixed(arrays_.state.eq),
               Fixed(arrays_.state.ep)};
      if (pending_) apply<kKahan, kFlow>(v, v, true, true, 0, nullptr, kicks_.stages());
      // (Entry by entry: Eigen's assignment of the sum to a VectorXd was a call of its
      // out-of-line loop per vector, ~30 instructions per output time at d = 1.)
      q.resize(D), p.resize(D);
      for (int e = 0; e < D; ++e) q[e] = v.q[e] + v.eq[e], p[e] = v.p[e] + v.ep[e];
    } else {
      const bool back = ahead_ && flows_.moves(0);
      if constexpr (kStaged) {
        if (back) return load_back_staged<kKahan>(q, p);
      }
      const State* from = &arrays_.state;
      if (back)
        apply<kKahan, kFlowBack>(arrays_.state, arrays_.work, true, true, 0, nullptr, 0),
            from = &arrays_.work;
      if constexpr (kStaged) {  // (the sum, scaled, into the second copy or the staging buffer)
        inverse_of_sum<kKahan>(from->q, from->eq, arrays_.work.q, q);
        inverse_of_sum<kKahan>(from->p, from->ep, arrays_.work.p, p);
        return;
      }
      if (kKahan) {
        map(arrays_.work.q) = map(from->q) + map(from->eq);
        map(arrays_.work.p) = map(from->p) + map(from->ep);
        from = &arrays_.work;
      }
      transform_.inverse(map(from->q), q);
      transform_.inverse(map(from->p), p);
    }
  }
  // load of a staged transform ahead: one pass (kFlowReadBack) applies flow 0 backwards and
  // writes q + eq (x alone without kKahan) and p + ep scaled into the second copy's q and p
  // (without inverse_scaled: q into the staging buffer), storing no state; their inverse
  // transforms read them there in place (inverse_scaled), the staging buffer kept where the
  // transform allows, or from copies in the staging buffer. Bit for bit the sums of the kFlowBack
  // pass and inverse_of_sum below (the same operations, their intermediates not stored): 9.5
  // streams of the state's size against 15.5 compensated. Reading the final state of
  // sine-Gordon N = 8192 Strang, plain: 1.35-1.53x the specialist's loop's read -> 1.14-1.16x;
  // compensated, with an output time at each of 10 steps, the output times' cost over the loop's
  // 1.16-1.29x -> 0.90-0.94x (N = 8192), 1.12-1.21x -> 0.96-1.00x (256^2; perf: inverse_of_sum's
  // two passes were 18 % of get_state). Pinned, alternated, medians.
  template <bool kKahan>
  void load_back_staged(Eigen::VectorXd& q, Eigen::VectorXd& p) {
    apply<kKahan, kFlowReadBack>(arrays_.state, arrays_.work, true, false, 0, nullptr, 0);
    if constexpr (kScaledInverse) {
      inverse_scaled(arrays_.work.q, q);
      inverse_scaled(arrays_.work.p, p);
    } else {
      transform_.inverse_staged(q);
      std::copy_n(lanes(arrays_.work.p), kLanes * arrays_.m, transform_.staging());
      transform_.inverse_staged(p);
      staged_ahead_ = false;
    }
  }
  // out = the physical vector of x + ex (x alone without kKahan), scaled into `scratch` (not x or
  // ex) and transformed from there (inverse_scaled), else through the staging buffer.
  template <bool kKahan>
  void inverse_of_sum(const Scalar* x, const Scalar* ex, Scalar* scratch, Eigen::VectorXd& out) {
    double* __restrict y = kScaledInverse ? lanes(scratch) : transform_.staging();
    const double* __restrict a = reinterpret_cast<const double*>(x);
    const double* __restrict b = reinterpret_cast<const double*>(ex);
    for (Eigen::Index j = 0; j < kLanes * arrays_.m; ++j)
      y[j] = stage_scale_ * (kKahan ? a[j] + b[j] : a[j]);
    if constexpr (kScaledInverse)
      inverse_scaled(scratch, out);
    else
      transform_.inverse_staged(out), staged_ahead_ = false;
  }
  // out = the physical vector of y (scaled as staged; y is lost) through the transform's
  // inverse_scaled, which may go through the staging buffer: the staged Q is then lost too.
  void inverse_scaled(Scalar* y, Eigen::VectorXd& out) {
    if (!transform_.inverse_scaled(y, out)) staged_ahead_ = false;
  }

  // A failed check (error() throws it): at once, or kept for settle() (kDeferred).
  template <class Throw>
  EIGEN_ALWAYS_INLINE void fail(Throw&& error) {
    if constexpr (kDeferred) {
      try {
        error();
      } catch (const Error& e) {
        transform_.defer(e);
      }
    } else {
      error();
    }
  }

  // The passes a step makes (explicit_passes.hpp, PassKind {kick, flow, in place, save, stage,
  // fold q, fold p, read, check, backward}): a flow, the first one staging Q (identity basis:
  // physical_.Q, else the transform's staging buffer, if any), get_state's (flow 0 backwards, or
  // a fixed dimension's pending flow) folding both (compensated) or, with a staging transform,
  // reading the state out (kFlowReadBack); kicks, the last one (alone, or with the merged flow)
  // saving the force to arrays_.G (identity basis), folding p and checking what it wrote; a kick
  // and the next flow, staging its Q. Compensated, the step's last flow folds q (apply's fold_q),
  // or else its last kick does.
  static constexpr bool kStage = kIdentity || kStaged;
  static constexpr PassKind kFlow{false, true, false, false, false, true, true, false};
  static constexpr PassKind kFlowStaged{false, true, false, false, kStage, false, false, false};
  static constexpr PassKind kFlowBack{false, true, false, false, false,
                                      true,  true, false, false, true};
  static constexpr PassKind kFlowReadBack{false, true, false, false, false,
                                          true,  true, true,  false, true};
  static constexpr PassKind kKick{true, false, true, false, false, false, false, false};
  static constexpr PassKind kKickLast{true,  false, true,  kIdentity, false,
                                      false, true,  false, true};
  static constexpr PassKind kKickFlowLast{true,  true, true,  false, kStage,
                                          false, true, false, true};
  static constexpr PassKind kKickFlow{true, true, true, false, kStage, false, false, false};
  static constexpr PassKind folding_q(PassKind kind) {
    kind.fold_q = true;
    return kind;
  }
  static constexpr PassKind placed(PassKind kind, bool in_place) {
    kind.in_place = in_place;
    return kind;
  }
  static constexpr PassKind bounding_p(PassKind kind) {
    kind.bound_p = true;
    return kind;
  }
  static constexpr PassKind over_start(PassKind kind) {
    kind.over_start = true;
    return kind;
  }
  static constexpr PassKind kKickFlowLastBounded = bounding_p(kKickFlowLast);

  // The pass `kind` from `start` into `to` (the step's first pass) or in place in `to`
  // (compensated: from `start` and the increments in `to`, folding q when fold_q) with the
  // kick's hd and g and flow k.
  template <bool kKahan, PassKind kind>
  EIGEN_ALWAYS_INLINE bool apply(const State& start, State& to, bool first, bool fold_q, double hd,
                                 const Scalar* g, int k) {
    if constexpr (kKahan && !kind.fold_q)
      if (fold_q) return apply<kKahan, folding_q(kind)>(start, to, first, false, hd, g, k);
    const PassArrays a = arrays(start), b = arrays(to);
    const auto f = kind.flow ? flow_of(k) : decltype(flow_of(k)){};  // (a kick has none)
    const double* gd = reinterpret_cast<const double*>(g);
    double* save = reinterpret_cast<double*>(arrays_.G);
    // (get_state's pass writes q into the second copy, as it does p, for inverse_scaled)
    double* Q = kind.read && kScaledInverse ? lanes(to.q) : stage_input();
    constexpr PassKind copy = placed(kind, false), in_place = placed(kind, true);
    if (!first) return pass<kKahan, in_place, kLanes>(n(), a, b, hd, gd, save, f, Q, stage_scale_);
    return pass<kKahan, copy, kLanes>(n(), a, b, hd, gd, save, f, Q, stage_scale_);
  }
  // (Fixed dimension: in place, whole arrays; Q and g checked by checked_gradient, the p a kick
  // wrote as it is in registers. The kick reads the callback's g entry by entry, callback_entries.)
  template <bool kKahan, PassKind kind>
  EIGEN_ALWAYS_INLINE bool apply(const Values&, Values& v, bool, bool, double hd, const Scalar* g,
                                 int k) {
    if constexpr (kind.kick) {
      kick_update<kKahan>(Fixed(-hd * callback_entries<D>(g)), v.q, v.p, v.eq, v.ep);
      if (kind.save)
        for (int e = 0; e < D; ++e) arrays_.G[e] = g[e];
    }
    std::uint64_t bits = 0;  // (the p a kick wrote, in registers; the last pass is a kick alone)
    if constexpr (kind.kick && !kind.flow)
      for (int e = 0; e < D; ++e) bits |= nonfinite_bits(v.p[e]);
    if constexpr (kind.flow) {
      flow_update<kKahan>(fixed(flows_.cosine(k)), fixed(flows_.sinc(k)), fixed(flows_.msinc(k)),
                          v.q, v.p, v.eq, v.ep);
      if (kind.stage)
        for (int e = 0; e < D; ++e) physical_.Q[e] = v.q[e];
    }
    return bits != 0;
  }

  // The arrays' passes run over doubles: a complex eigen coordinate (half spectrum) is kLanes = 2
  // of them, re and im, which share their real coefficients.
  static constexpr int kLanes = int(sizeof(Scalar) / sizeof(double));
  static PassArrays arrays(const State& x) {
    auto d = [](Scalar* y) { return reinterpret_cast<double*>(y); };
    return {d(x.q), d(x.p), d(x.eq), d(x.ep)};
  }
  // Flow k's coefficients: the one value of each (scalar M) or pointers to the arrays.
  EIGEN_ALWAYS_INLINE auto flow_of(int k) const {
    if constexpr (std::is_same_v<Coef, double>)
      return PassFlow<double>{flows_.cosine(k), flows_.sinc(k), flows_.msinc(k)};
    else
      return PassFlow<const double*>{flows_.cosine(k).data(), flows_.sinc(k).data(),
                                     flows_.msinc(k).data()};
  }

  // The force at the stage q (eigen coordinates; already in physical_.Q when have_Q, and known
  // finite when finite_Q), evaluated in physical coordinates: in eigen coordinates in arrays_.G,
  // or (identity basis) in physical_.g. A modified kick's force is d_i g + h^2 e_i G.
  EIGEN_ALWAYS_INLINE const Scalar* evaluate(const Scalar* q, bool have_Q, bool finite_Q, int i,
                                             Counts& evaluations) {
    // (With arrays the kick checks the force; a modified one's g is checked before G(Q, g).)
    return force(q, have_Q, finite_Q, i, method_.table().d[i], kicks_.h2e(i), evaluations,
                 kFixed || kicks_.h2e(i) != 0);
  }
  // The force d_i g + h2e G at q (d_i unused for a plain kick, h2e = 0), as evaluate; g checked
  // finite when check_g.
  EIGEN_ALWAYS_INLINE const Scalar* force(const Scalar* q, bool have_Q, bool finite_Q, int i,
                                          double d_i, double h2e, Counts& evaluations,
                                          bool check_g) {
    if constexpr (kIdentity) {
      if (!have_Q) std::copy_n(q, n(), physical_.Q.data());
    } else if constexpr (kStaged) {
      if (have_Q)
        transform_.inverse_staged(physical_.Q);
      else
        transform_.inverse(ConstMap(q, arrays_.m), physical_.Q);
    } else {
      transform_.inverse(ConstMap(q, arrays_.m), physical_.Q);
    }
    if constexpr (kDeferred) {  // (no modified kicks: the distributed integrator refuses them)
      transform_.gradient(system_, physical_.Q, physical_.g, i, place_, evaluations.gradients);
      transform_.to_eigen_force(physical_.Q, ConstMap(q, arrays_.m), physical_.g, map(arrays_.G));
      return arrays_.G;
    }
    const auto gradient = [&](const Vector& Q, Vector& g) { gradient_(system_, Q, g); };
    checked_gradient<D>(gradient, physical_.Q, physical_.g, physical_.Q.size(), i, place_,
                        evaluations.gradients, check_g, !finite_Q);
    if (rkn_)
      on_vectors([&](const Eigen::VectorXd& Q, Eigen::VectorXd& g) {
        M_->apply(Q, physical_.Mq);
        g += physical_.Mq;
      });
    if constexpr (Gradient::kProduct) {
      if (h2e != 0)
        modified_.apply_compiled<D>(gradient_, physical_.Q, d_i, h2e, physical_.g, i, place_,
                                    evaluations.products);
    } else if (h2e != 0) {
      on_vectors([&](const Eigen::VectorXd& Q, Eigen::VectorXd& g) {
        modified_.apply<D>(system_, Q, d_i, h2e, g, i, place_, evaluations.products);
      });
    }
    if constexpr (kIdentity) {
      return physical_.g.data();
    } else {
      transform_.forward(physical_.g, map(arrays_.G));
      return arrays_.G;
    }
  }

  // f(Q, g) on the stage's Q and g as Eigen::VectorXd: themselves, or (fixed-size vectors) exact
  // copies, g copied back.
  template <class F>
  EIGEN_ALWAYS_INLINE void on_vectors(F&& f) {
    if constexpr (kDynamicVector) {
      f(physical_.Q, physical_.g);
    } else {
      physical_.x->Q = physical_.Q, physical_.x->g = physical_.g;
      f(physical_.x->Q, physical_.x->g);
      physical_.g = physical_.x->g;
    }
  }

  static int last_moving_flow(const FlowCoefficients<Coef>& flows, int s) {
    for (int k = s - 1; k > 0; --k)
      if (flows.moves(k)) return k;
    return 0;
  }

  // M applied in physical coordinates (none with a deferred space: it applies M itself).
  static std::optional<MOperator> m_operator(const Stiffness& M, Eigen::Index d) {
    if constexpr (kDeferred)
      return std::nullopt;
    else
      return std::optional<MOperator>(std::in_place, M, d);
  }

  static double staging_scale(const Transform& t) {
    if constexpr (kStaged)
      return t.staging_scale();
    else
      return 1;
  }
  // Where the flow before a gradient writes the stage's q (as doubles), or nullptr.
  double* stage_input() {
    if constexpr (kIdentity)
      return physical_.Q.data();
    else if constexpr (kStaged)
      return transform_.staging();
    else
      return nullptr;
  }

  // A step over arrays of at least this many bytes each may be in place (in_place_steps).
  static constexpr std::size_t kInPlaceBytes = 256 * 1024;
  // Whether a step's pass may overwrite its start (last_pass): over arrays of at least
  // kInPlaceBytes, whose working set the second copy takes out of the caches (2-D sine-Gordon
  // 256^2, 528 KiB arrays, Strang, gradient compiled in, erkn / the specialist's loop in
  // erkn_integrate_benchmark --short, three runs of each build alternated with main a5b5e7e, Intel
  // Xeon: compensation off 0.998-1.004 -> 0.959-0.980, defaults 1.148-1.156 -> 1.041-1.078, with
  // output times 1.109-1.115 -> 1.056-1.082; perf: the pass 11.8 -> 6.8 % of a plain run; the
  // same step in place at N = 8192, 64 KiB arrays, changed nothing), of a method of one stage (its
  // step is one pass; earlier passes would overwrite a start the later ones read), with checks
  // that are not deferred (a deferred failure is thrown after the pass), the merged flow's
  // coefficients at most kFlowBound and a staged Q at least 2^-40 of q (explicit_passes.hpp,
  // kPBound).
  static constexpr bool kMayStepInPlace = !kFixed && !kDeferred && kStage;
  bool in_place_steps() const {
    if constexpr (!kMayStepInPlace) {
      return false;
    } else {
      const auto largest = [](const auto& x) -> double {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, double>)
          return std::abs(x);
        else
          return x.abs().maxCoeff();
      };
      const int k = flows_.merged(method_);
      return ends_ahead_ && kicks_.stages() == 1 &&
             std::size_t(n()) * sizeof(Scalar) >= kInPlaceBytes && stage_scale_ >= 0x1p-40 &&
             largest(flows_.cosine(k)) <= kFlowBound && largest(flows_.sinc(k)) <= kFlowBound &&
             largest(flows_.msinc(k)) <= kFlowBound;
    }
  }

  // The number of eigen coordinates (a constant when D is).
  Eigen::Index n() const {
    if constexpr (kFixed)
      return D;
    else
      return arrays_.m;
  }

  // A coefficient as a fixed-size array (or the one value of a scalar M).
  static double fixed(double value) { return value; }
  template <class Map>
  static Fixed fixed(const Map& values) {
    return Fixed(values.data());
  }

  // x into eigen coordinates at y (a fixed dimension: its D entries, without the out-of-line
  // assignment loop of a map).
  void forward(const Eigen::VectorXd& x, Scalar* y) {
    if constexpr (kFixed)
      std::copy_n(x.data(), D, y);
    else
      transform_.forward(x, map(y));
  }

  // An array of the storage as an Eigen array.
  SpectralMap map(Scalar* x) const { return {x, arrays_.m}; }

  Method method_;
  System system_;
  bool kahan_, rkn_;
  bool in_place_ = false;  // (in_place_steps, set by the constructor)
  KickWeights kicks_;
  FlowCoefficients<Coef> flows_;
  Transform transform_;
  double stage_scale_ = staging_scale(transform_);  // (what stage_input wants)
  std::optional<MOperator> M_;
  Arrays arrays_;
  Physical physical_;
  [[no_unique_address]] Gradient gradient_;
  ModifiedForce modified_;
  std::unique_ptr<Processing> processing_;
  // Over arrays the state after a step runs ahead, after flow 0 of the next (with its first Q
  // staged: staged_ahead_, below kStageBound: bounded_ahead_), when the merged flow or flow s
  // moves (c_s - c_1 = 1: flows s and 0 cancel, and the last pass makes the merged flow of 0); a
  // fixed dimension's awaits flow s (the last of the step) when it moves.
  bool ends_ahead_ = !kFixed && (flows_.moves(flows_.merged(method_)) ||
                                 flows_.moves(kicks_.stages()));  // (ahead_ after a step)
  bool ends_pending_ = kFixed && flows_.moves(kicks_.stages());   // (pending_ after a step)
  bool ahead_ = false, staged_ahead_ = false, bounded_ahead_ = false;
  bool pending_ = false;
  bool have_history_ = false;
  // The last of flows 1 .. s - 1 that moves (0: none; -1: ahead, q's increments complete only
  // after the last pass's flow), after which q's increments are complete.
  // (A byte: with an int the stepper of d = 4 outgrew the blocks glibc's per-thread cache serves.)
  std::int8_t last_flow_ =
      std::int8_t(ends_ahead_ ? -1 : last_moving_flow(flows_, method_.stages()));
  StepPlace place_{&method_, 0, 0};
};

}  // namespace erkn::detail
