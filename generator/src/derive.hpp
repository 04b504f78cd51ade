// From a MethodSpec to the method: solves the symplectic, quadrature, coupling and diagonal
// conditions symbolically (GiNaC lsolve over symbolic c_i, so the general formulas such as
// c2 = (2 - 3 c1)/(3 - 6 c1) appear on the way), substitutes the nodes, brings every coefficient
// to trigonometric normal form and verifies every imposed condition identically.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "certify.hpp"
#include "processing.hpp"
#include "spec.hpp"
#include "trig.hpp"

namespace erkn::gen {

/// One coefficient function of the tableau and everything known about it.
struct Coefficient {
  std::string name;      ///< b1, bbar1, abar21, ...
  Rational closed_form;  ///< den = 1 except for the solved diagonal
  /// How it was solved, in the symbols of the paper (GiNaC syntax), e.g.
  /// "abar11 = (bbar2*phi(3,v)-b2*phi(4,v))/(b1*bbar2-b2*bbar1)".
  std::string derivation;
  std::vector<Qs> series;     ///< exact Taylor coefficients, kSeriesTerms
  std::vector<double> poles;  ///< real poles in v, ascending (locate_poles())
  double series_switch = 0;   ///< the series below, the closed form above (locate_poles())
};

struct Derived {
  MethodSpec spec;
  std::vector<Qs> c, d;
  /// Modified-kick coefficients: stage i kicks p -= h (d_i grad U + h^2 e_i grad(|grad U|^2));
  /// empty for plain kicks.
  std::vector<Qs> e;
  /// A processed method's pre-processor pi^-1 (empty: not processed); c, d, e are then the
  /// kernel K of psi = pi o K o pi^-1.
  Processor pre;
  /// In table order: b_1..b_s, bbar_1..bbar_s, abar_11, abar_21, abar_22, ...
  std::vector<Coefficient> coefficients;
  std::vector<std::string> node_derivation;  ///< c and d as functions of the free nodes
  /// Order conditions of eq. (f), checked: of psi = pi o K o pi^-1 for a processed method
  /// (its effective order), else of the method.
  Certificate certificate;
  Certificate kernel_certificate;  ///< a processed method's kernel K alone (its own order)
  Certificate rkn_certificate;     ///< the same for the V -> 0 limit (if spec.rkn is set)
  double certify_seconds = 0;      ///< wall time of both certifications
  /// Conditions of the claim that the spec's decimals miss by more than 1e-8 (Polished::unmet):
  /// the certification then refuses the claim.
  int unmet_by_decimals = 0;
  int stages() const { return spec.stages; }
};

inline constexpr int kSeriesTerms = 25;
/// Order conditions are checked up to this power of h (or the claimed order + 1 if higher):
/// enough for the generalized orders (8, 6, 4) of the near-integrable methods.
inline constexpr int kCertifyPowers = 10;

/// Index of abar_ij (1-based i >= j) in Derived::coefficients.
inline int abar_index(int s, int i, int j) { return 2 * s + i * (i - 1) / 2 + (j - 1); }

/// Solves, verifies and certifies; throws std::runtime_error naming the method and the condition
/// that fails.
Derived derive(const MethodSpec& spec);

/// Certifies the order of a derived method and of its V -> 0 limit (eq. (f) over the SEN-trees);
/// throws naming the method, the first failing tree and its residual if the claimed order fails.
void certify_order(Derived& m);

using TrigEnv = std::map<GiNaC::ex, Rational, GiNaC::ex_is_less>;

/// A GiNaC expression in numbers, sqrt(n), v, phi(j, w*v) and the symbols of `env`, in normal
/// form. Used by derive() and by the symbolic tests on the emitted closed forms.
Rational to_rational(const GiNaC::ex& e, const TrigEnv& env, const GiNaC::symbol& v);

}  // namespace erkn::gen
