// Processed methods psi = pi o K o pi^-1 (docs/design.md, "Processing"): the kernel K steps,
// the processor pi is paid only where a state is looked at, and psi^n = pi o K^n o pi^-1. The
// effective order is psi's, an explicit method itself: pi^-1 (the spec's pre-sequence), then K,
// then pi, which is pi^-1 run backwards with every drift and kick negated (the exact inverse of
// an exact flow or a kick; not the adjoint, which keeps the coefficients). Its drifts sum to
// T + 1 - T = 1, so the tree conditions of eq. (f) certify it as they certify any splitting.
#pragma once

#include <vector>

#include "qs.hpp"

namespace erkn::gen {

/// The pre-processor pi^-1: drift drift[0] h, kick by (kick[0], modified[0]), drift drift[1] h,
/// ..., with one drift per kick and optionally a last one; modified empty for plain kicks.
struct Processor {
  std::vector<Qs> drift, kick, modified;
  bool empty() const { return kick.empty(); }
  /// Total drift T (in units of h).
  Qs total() const;
};

/// An explicit method as kicks at nodes c (cumulative drift) with weights d and modified-kick
/// coefficients e (empty: plain), the last drift closing the step at 1.
struct KickSequence {
  std::vector<Qs> c, d, e;
};

/// psi = pi o K o pi^-1 as one explicit method: the kicks of pi^-1 at their cumulative drifts
/// c^pre_k, K's at T + c_i, and pi's at 1 + c^pre_k (k descending) with -kick, -modified.
/// The kernel alone (pre empty) is returned as it is.
KickSequence composition(const std::vector<Qs>& c, const std::vector<Qs>& d,
                         const std::vector<Qs>& e, const Processor& pre);

}  // namespace erkn::gen
