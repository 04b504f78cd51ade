// The nodes the stage predictor (stage_predictor.hpp) extrapolates each stage's gradient through,
// and their Lagrange weights: they depend only on the method's nodes c, so they are formed once
// per method and process, not per Stepper. (Formed per construction, set_nodes and the weights'
// allocation and free were ~590 of the ~7,250 instructions of a construct + 1-step run of
// SERKN2s3 at P3: callgrind.)
#pragma once

#include <array>
#include <memory>

#include "erkn/method.hpp"

namespace erkn::detail {

// Steps back whose stage gradients the starting values extrapolate from. One: three predicted
// better at fine h on P1-P3, but their higher degrees let the modes with large abar_ii of P1 at
// N = 2048 diverge (SERKN3s4(1), h = 1/32: 9.4 evaluations per stage and 23 Newton fallbacks
// instead of 3.8, 7).
inline constexpr int kPredictorHistory = 1;
inline constexpr int kMaxPredictorNodes = (kPredictorHistory + 1) * kMaxStages;

struct StageNodes {
  struct Node {
    int age, stage;  // age 0: this step
  };
  int n = 0;  // nodes at most: (kPredictorHistory + 1) s
  // Stage i's nodes, most recent first (count[i] of them), and each one's array among the steps'
  // arrays (this step's stages first): age s + stage.
  std::array<std::array<Node, kMaxPredictorNodes>, kMaxStages> nodes;
  std::array<std::array<int, kMaxPredictorNodes>, kMaxStages> offset;
  std::array<int, kMaxStages> count{};
  // weight(i, m - 1, l) = weights[(i n + m - 1) n + l]: node l's Lagrange weight at c_i on the
  // first m nodes (l < m <= count[i]; the others unset).
  std::unique_ptr<double[]> weights;
};

/// The method's nodes and weights, formed at the first call for its table and kept for the
/// process (thread-safe; a thread's repeated calls for one method take no lock).
const StageNodes& stage_nodes(const Method& method);

}  // namespace erkn::detail
