// The starting values of the stage solver (stage_solver.hpp): stage i's gradient extrapolated
// through its order(i) most recent known stage gradients (nodes: this step's stages j < i, then
// those of the kHistory steps before), with the order adapted to what predicts best. It also
// keeps the stage gradients themselves: G(i) of this step, and of the steps before it.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>

#include "erkn/method.hpp"
#include "implicit_passes.hpp"
#include "stage_checks.hpp"
#include "stage_nodes.hpp"

namespace erkn::detail {

/// Calls f(a) with `a` the array to compute `out` in: with a fixed size (tiny systems) a value
/// the compiler keeps in registers, stored to `out` once; with a dynamic size `out` itself (a
/// value would allocate). (Every vector store through a map may alias anything, so a sum built
/// in a map made the compiler reload each coefficient and view after each term: P3, d = 2.)
/// (Always inlined: a call of its own cost more than it saves at d = 1.)
template <class Out, class F>
[[gnu::always_inline]] inline void compute_into(Out& out, F&& f) {
  if constexpr (Out::RowsAtCompileTime == Eigen::Dynamic) {
    f(out);
  } else {
    typename Out::PlainObject value;
    f(value);
    out = value;
  }
}

template <class Space>
class StagePredictor {
 public:
  using Map = typename Space::Map;
  using Scalar = typename Space::Scalar;
  static constexpr int kHistory = kPredictorHistory;  // (stage_nodes.hpp)
  static constexpr int kMaxNodes = kMaxPredictorNodes;

  StagePredictor(const Method& method, const Space& space)
      : space_(space),
        s_(method.stages()),
        n_((kHistory + 1) * s_),
        block_(space.template block<kMaxNodes>(n_)) {
    for (int age = 0; age <= kHistory; ++age) steps_[age] = space.map(block_, age * s_).data();
    set_nodes(stage_nodes(method));
    set_uses();
  }
  StagePredictor(const StagePredictor&) = delete;  // (steps_ points into block_)
  StagePredictor& operator=(const StagePredictor&) = delete;

  /// Stage i's gradient of this step.
  Map G(int i) {
    if constexpr (kInPlace)
      return space_.map(block_.data(), i);
    else
      return gradient_at(0, i);
  }
  /// Forgets the steps before (set_state, a new start).
  void reset() {
    history_ = 0;
    adapt_wait_.fill(1);
    adapt_interval_.fill(1);
    set_uses();
  }
  /// After a step: this step's gradients become the previous step's: with a fixed size moved
  /// back by one step in place (s D values), so that every node keeps its address (predict's
  /// offsets); else the steps' pointers rotated. S: the stage count when the caller knows it at
  /// compile time (StageSolver::for_each_stage), else 0.
  template <int S = 0>
  void advance() {
    if constexpr (kInPlace) {  // (array by array: std::copy_n of s D values was a memmove call)
      // (s in a local: each store may alias s_, which GCC reloaded after it.)
      const int s = S > 0 ? S : s_;
      for (int age = kHistory; age > 0; --age)
        for (int j = 0; j < s; ++j)
          space_.map(block_.data(), age * s + j) =
              stored_force(space_.map(block_.data(), (age - 1) * s + j));
    } else {
      Scalar* const oldest = steps_[kHistory];  // (rotated by hand: std::rotate was a call)
      for (int age = kHistory; age > 0; --age) steps_[age] = steps_[age - 1];
      steps_[0] = oldest;
    }
    if (history_ < kHistory) ++history_, set_uses();
  }
  /// Whether the steps before are known (after a reset the first guesses are poor).
  bool has_history() const { return history_ > 0; }

  /// out = stage i's predicted gradient (0 when no node is known yet).
  template <class Out>
  void predict(int i, Out& out) {
    if (use_[i] > 0)
      compute_into(out, [&](auto& value) { predict(i, use_[i], use_weights_[i], value); });
    else
      out.setZero();
  }
  /// With a fixed size: stage i's prediction without its newest node, rest = sum_{l >= 1} w_l
  /// node_l (oldest first), and that node's weight w_0 (0 with no node); the caller adds w_0 times
  /// the newest node last. The nodes read through at(offset) (offset: the node's array among the
  /// steps' arrays, this step's stages first): stored() for the nodes as they are (for i > 0 the
  /// newest is this step's G_{i-1}: StageSolver::start_fixed), next() for stage 0 of the next step
  /// formed before advance() (StageSolver::carry; valid when the history is full, so advance then
  /// changes no weight).
  template <class Out, class At>
  double predict_rest(int i, Out& rest, At&& at) const {
    static_assert(kInPlace);
    rest.setZero();
    for (int l = use_[i] - 1; l >= 1; --l) rest += use_weights_[i][l] * at(offset_[i][l]);
    return use_[i] > 0 ? use_weights_[i][0] : 0.0;
  }
  /// predict_rest's readers: the node at an offset, or (next) the node one step younger.
  auto stored() {
    return [this](int offset) { return stored_force(space_.map(block_.data(), offset)); };
  }
  auto next() {
    return [this](int offset) { return stored_force(space_.map(block_.data(), offset - s_)); };
  }
  /// Whether the steps before are all known (advance changes no node's weight).
  bool full_history() const { return history_ == kHistory; }
  /// Counts a step of stage i towards its next order check; true when it is due (adapt). Never
  /// due for a stage with fewer than two nodes (one-stage methods: adapt has no order to choose;
  /// its call was 4 % of P2's instructions for SERKN1s2(1), callgrind).
  bool adapt_due(int i) { return node_count_[i] >= 2 && --adapt_wait_[i] <= 0; }
  template <class Abar>
  void adapt(int i, const Abar& abar_ii, Map& prediction, Map& below, Map& above);

 private:
  void set_nodes(const StageNodes& formed);
  // |h^2 abar_ii (g_pred - g_i)|^2 (this process's part) of stage i's prediction through m nodes
  // (m = 0: the one in `guess`), formed in `guess`, or with a fixed size in a value the compiler
  // keeps in registers (guess then unchanged: through the maps, adapt stored and reloaded each
  // guess, P3).
  template <class Abar>
  double guess_error(int i, int m, const Abar& abar_ii, Map& guess) {
    const auto error = [&](auto& g) {
      if (m > 0) predict(i, m, &weight(i, m - 1, 0), g);
      g = abar_ii * (g - G(i));
      return space_.squared_norm(g);
    };
    if constexpr (Map::RowsAtCompileTime == Eigen::Dynamic) {
      return error(guess);
    } else {
      typename Map::PlainObject value;
      if (m == 0) value = guess;
      return error(value);
    }
  }
  // Nodes of stage i whose gradients are known (the steps since set_state).
  int available_nodes(int i) const {
    if (history_ == kHistory) return node_count_[i];  // (every node: the usual case)
    int n = 0;
    while (n < node_count_[i] && nodes_[i][n].age <= history_) ++n;
    return n;
  }
  // out = the polynomial through the first n nodes of stage i, at c_i (w: their weights): over
  // arrays in one pass (implicit_passes.hpp's predict_pass), else as expressions.
  template <class Out>
  void predict(int i, int n, const double* w, Out& out) {
    if constexpr (Out::RowsAtCompileTime == Eigen::Dynamic) {
      constexpr int kLanes = int(sizeof(Scalar) / sizeof(double));
      std::array<const double*, kMaxNodes> g;
      for (int l = 0; l < n; ++l) g[size_t(l)] = reinterpret_cast<const double*>(node(i, l).data());
      predict_pass<kLanes>(out.size(), g.data(), w, n, reinterpret_cast<double*>(out.data()));
    } else {
      out = w[0] * node(i, 0);
      for (int l = 1; l < n; ++l) out += w[l] * node(i, l);
    }
  }
  // Node l of stage i: with a fixed size at its offset in block_ (a constant address: the
  // lookup of its step's pointer and its index were ~5 of ~9 instructions per node of the
  // prediction, P2), else through its step's pointer.
  Map node(int i, int l) {
    if constexpr (kInPlace)
      return space_.map(block_.data(), offset_[i][l]);
    else
      return gradient_at(nodes_[i][l].age, nodes_[i][l].stage);
  }
  Map gradient_at(int age, int stage) {
    return space_.map(steps_[age], stage);  // (steps_[age]: the first of s arrays)
  }
  // use_[i] = the nodes predict(i) uses, min(order_[i], available_nodes(i)), and their weights,
  // renewed whenever either changes (reset, advance's first steps, adapt): found at every
  // prediction they were ~20 of its ~35 instructions (P2, SERKN2s3).
  void set_use(int i) {
    use_[i] = std::min(order_[i], available_nodes(i));
    use_weights_[i] = use_[i] > 0 ? &weight(i, use_[i] - 1, 0) : nullptr;
  }
  void set_uses() {
    for (int i = 0; i < s_; ++i) set_use(i);
  }
  // weight(i, m - 1, l): node l's Lagrange weight at c_i on the first m nodes (stage_nodes.hpp).
  const double& weight(int i, int m, int l) const {
    return weights_[(size_t(i) * n_ + m) * n_ + l];
  }

  using Node = StageNodes::Node;
  static constexpr int kMaxAdaptInterval = 64;
  // Whether the gradients of the steps before stay in block_ at fixed places (advance).
  static constexpr bool kInPlace = Space::kFixed;
  const Space& space_;
  int s_;
  int n_;  // nodes at most: (kHistory + 1) s
  // Copied from stage_nodes (the prediction reads them at fixed offsets from `this`). (Not
  // value-initialised: set_nodes writes node_count_[i] entries of stage i before any is read.
  // Zeroed, their 4.7 KB at kMaxStages = 14 were ~650 of the ~10,000 instructions of a
  // Stepper's construction, P3, SERKN2s3: callgrind.)
  std::array<std::array<Node, kMaxNodes>, kMaxStages> nodes_;
  std::array<std::array<int, kMaxNodes>, kMaxStages> offset_;  // node's array in block_
  std::array<int, kMaxStages> node_count_{}, order_{}, use_{};
  std::array<const double*, kMaxStages> use_weights_{};
  const double* weights_ = nullptr;  // stage_nodes(method).weights
  int history_ = 0;                  // steps before this one with stage gradients (since set_state)
  std::array<int, kMaxStages> adapt_wait_{}, adapt_interval_{};  // steps to adapt's check
  alignas(EIGEN_MAX_ALIGN_BYTES) typename Space::template Block<kMaxNodes> block_;  // s per step
  std::array<Scalar*, kHistory + 1> steps_{};
};

// The method's nodes (stage_nodes.hpp), each stage's first at order n (every node it has).
template <class Space>
void StagePredictor<Space>::set_nodes(const StageNodes& formed) {
  for (int i = 0; i < s_; ++i) {
    const int n = formed.count[i];
    std::copy_n(formed.nodes[i].begin(), n, nodes_[i].begin());
    std::copy_n(formed.offset[i].begin(), n, offset_[i].begin());
    node_count_[i] = order_[i] = n;
    adapt_wait_[i] = adapt_interval_[i] = 1;
  }
  weights_ = formed.weights.get();
}

// Called after stage i is solved (G(i) known) with predict(i)'s result in `prediction` (with a
// fixed size: unused, the prediction formed anew), when
// adapt_due(i) (every adapt_interval steps): moves stage i's order n to whichever of n - 1, n, n +
// 1 nodes would have given the solved stage the best guess, |h^2 abar_ii(V) (g_pred - g_i)|: high
// degrees where the stage gradients are smooth on the scale of h, low ones where they oscillate
// (the extrapolation then amplifies more than it predicts, most harmfully in the modes with large
// abar_ii). Checked every step while the order moves; each check that keeps it doubles the interval
// to the next, up to kMaxAdaptInterval steps: checked at every step, its two more predictions and
// norms per stage cost P2/P3 15-20% of the CPU per grad U (erkn_implicit_benchmark) and saved
// no evaluation there; with the interval, evaluations per stage (erkn_stage_evaluations) moved
// by <= 0.05 on P1-P3, and P1's savings (SERKN3s4(1) at 1e-9: 1.13 against 1.42) stay.
// kMaxAdaptInterval 64, not 8: at 8 the checks still cost P2 and P3 ~3 % of the CPU per grad U
// (knock-out and 64 against 8, A/B in one process: median -2.8 % P2, -3 % P3).
// prediction, below and above may be overwritten (guess_error; the errors of n, n - 1 and n + 1
// nodes in one reduce).
template <class Space>
template <class Abar>
void StagePredictor<Space>::adapt(int i, const Abar& abar_ii, Map& prediction, Map& below,
                                  Map& above) {
  const int available = available_nodes(i), n = std::min(order_[i], available);
  if (available < 2) return;  // (adapt_wait_ <= 0: checked at the next step)
  const std::array<int, 3> orders{n, n - 1, n + 1};
  std::array<Map*, 3> guesses{&prediction, &below, &above};
  std::array<double, 3> errors{};  // (squared: only compared)
  // (With a fixed size `prediction` was not formed: start_fixed splits it; predicted here anew.)
  for (int k = 0; k < 3; ++k)
    if (orders[k] >= 1 && orders[k] <= available)
      errors[k] = guess_error(i, k == 0 && !kInPlace ? 0 : orders[k], abar_ii, *guesses[k]);
  errors = space_.reduce(errors);
  double best = errors[0];
  int best_n = n;
  for (int k = 1; k < 3; ++k)
    if (orders[k] >= 1 && orders[k] <= available && errors[k] < best)
      best = errors[k], best_n = orders[k];
  adapt_interval_[i] =
      best_n == order_[i] ? std::min(2 * adapt_interval_[i], kMaxAdaptInterval) : 1;
  adapt_wait_[i] = adapt_interval_[i];
  order_[i] = best_n;
  set_use(i);
}

}  // namespace erkn::detail
