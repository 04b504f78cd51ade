// Polishing decimal coefficients: an explicit method transcribed from the literature as decimals
// (16-30 digits) satisfies its order conditions only to that precision. A minimum-norm Newton
// correction moves (c, d, e) onto the conditions in Qs::kApproxDigits-digit arithmetic, keeping the
// symmetry c_i + c_(s+1-i) = 1, d_i = d_(s+1-i) when the decimals have it and the nodes or weights
// given exactly (a drift 0: a kick at c = 0), so that the emitted
// doubles are the correctly rounded values of a method that satisfies them.
#pragma once

#include <string>
#include <vector>

#include "processing.hpp"
#include "qs.hpp"

namespace erkn::gen {

struct Polished {
  std::vector<Qs> c, d, e;     ///< e: modified-kick coefficients (empty: none)
  Processor pre;               ///< the polished pre-processor (processed methods)
  double correction = 0;       ///< largest |change| of a c_i, d_i or e_i
  double residual_before = 0;  ///< largest |residual| of the conditions polished onto
  double residual_after = 0;
  int conditions = 0;  ///< how many conditions
  int unmet = 0;       ///< conditions of the claim left out: beyond the orders the decimals meet
  bool symmetric = false;
  std::string summary() const;  ///< one line for derivation.md
};

/// Newton onto every condition of eq. (f) of power <= order and, for K = 1.., those of the trees
/// with K f-vertices of power <= generalized[K-1]. If the decimals miss some of these by more
/// than 1e-8 (a claim they do not satisfy, or a transcription error), polishes onto the orders
/// they meet (`unmet` > 0: the conditions left out) so that the certification refuses the claim
/// naming a tree. Throws (naming
/// `method`) if no such polishing is within 1e-8 of the decimals with every residual below 1e-50.
/// Modified kicks (e non-empty) are polished with c and d (a stage's e_i given exactly, such
/// as 0 for a plain kick, stays as given). A processed method (pre non-empty) is polished onto
/// the conditions of psi = pi o K o pi^-1 (processing.hpp), the processor's decimals with the
/// kernel's.
Polished polish_explicit(const std::string& method, std::vector<Qs> c, std::vector<Qs> d,
                         std::vector<Qs> e, int order, const std::vector<int>& generalized,
                         const Processor& pre = {});

}  // namespace erkn::gen
