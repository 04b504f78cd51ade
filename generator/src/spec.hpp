// Reading generator/methods.spec: one block of `key value` lines per method (the syntax is
// documented at the top of methods.spec).
#pragma once

#include <istream>
#include <string>
#include <vector>

namespace erkn::gen {

enum class SpecKind { erkn, explicit_erkn };

struct MethodSpec {
  std::string name;  ///< e.g. "SERKN3s4(1)"
  SpecKind kind = SpecKind::erkn;
  std::string rkn;     ///< the name of its V -> 0 limit (empty: none emitted)
  std::string source;  ///< where the method comes from (paper section, article and table)
  bool paper = false;  ///< given by `section`: a method of the source paper (Shi, Zhang & Wang)
  int stages = 0;
  int order = 0;  ///< claimed; erkn-generate refuses the spec unless it certifies it
  /// Claimed generalized order for H = A + eps B: order in h of the eps^K terms, K = 1, 2, ...
  std::vector<int> generalized;
  /// GiNaC syntax (decimals read exactly as written), or "?" for a value the generator solves.
  std::vector<std::string> c, d;
  /// Modified-kick coefficients (`modified`): stage i kicks p -= h (d_i grad U + h^2 e_i
  /// grad(|grad U|^2)). Empty: plain kicks. Explicit methods only.
  std::vector<std::string> e;
  /// Processed methods, psi = pi o K o pi^-1 (c, d, e are the kernel K): the pre-processor
  /// pi^-1 that the runtime applies to a user's state before the kernel steps, as written:
  /// drift pre_drift[0] h, kick pre_kick[0] (modified: pre_modified[0]), drift pre_drift[1] h, ...
  /// (one drift per kick, and optionally a last one). Its inverse pi maps the kernel's state to
  /// the one a user sees. Empty: not processed.
  std::vector<std::string> pre_drift, pre_kick, pre_modified;
  bool processed() const { return !pre_kick.empty(); }
  std::vector<std::string> drift;     ///< as written; c_i = drift_1 + ... + drift_i
  std::string drift_sum;              ///< sum of all s+1 drifts when `drift` gives them: must be 1
  std::vector<std::string> diagonal;  ///< equations `lhs == rhs` fixing abar_ii (kind erkn)
  int line = 0;                       ///< where the block starts in the spec
};

/// C identifier for a method name: "SERKN3s4(1)" -> "SERKN3s4_1", "ABA(8,6,4)" -> "ABA_8_6_4".
std::string identifier(const std::string& name);

/// Throws std::runtime_error naming the line (or method) of a malformed spec.
std::vector<MethodSpec> read_specs(std::istream& in);

}  // namespace erkn::gen
