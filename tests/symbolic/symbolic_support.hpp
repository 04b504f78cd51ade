// Shared machinery of the symbolic checks: exact numbers, Taylor series by GiNaC's own series(),
// the emitted methods read back from generated/, and the conditions of the paper (Theorem 1,
// eq. (f); Theorem 2, eq. (g); the diagonal choices of Section 3) as GiNaC expressions that can be
// checked exactly (trigonometric normal form) or as truncated series in V.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "derive.hpp"
#include "erkn/generated/tables.hpp"
#include "paper_series.hpp"
#include "phi.hpp"
#include "qs.hpp"
#include "trig.hpp"

namespace erkn::symtest {

using gen::Qs;
/// Coefficients of V^0, V^1, ... of a power series (truncated).
using Series = std::vector<Qs>;

/// The name of the coefficient abar_ij in the tables (abar21, ...).
std::string abar_name(int i, int j);
/// A table's text with every decimal literal (0.125, 1.5e-3) replaced by the exact rational of
/// the digits written, so that decimal coefficients enter the exact arithmetic as given.
std::string exact_text(const std::string& text);

/// The symbol v (scalar stand-in for V) of every parsed expression.
const GiNaC::symbol& vsym();
/// The unique symbol of a name (b1, bbar2, abar21, ...), so that expressions built in different
/// places share it.
const GiNaC::symbol& sym(const std::string& name);
/// Parses GiNaC syntax in v, phi(j, x), sqrt and the named symbols (b1, ..., abar33, c1, d1, ...).
GiNaC::ex parse(const std::string& text);

/// Exact value in Q(sqrt(s)) of a constant expression: rationals, sqrt(n), +, *, integer powers.
/// Independent of the generator's parsing (only Qs arithmetic is shared).
Qs exact_number(const GiNaC::ex& e);

/// Taylor coefficients of V^0..V^(n-1) of an emitted closed form: GiNaC's series() of numerator
/// and denominator (phi's series_func), each coefficient brought to a + b*sqrt(s), then the exact
/// power-series quotient (the removable 0/0 at v = 0 of the solved diagonals is handled here).
Series ginac_taylor(const GiNaC::ex& e, int n);
/// The same via the generator's normal form: to_rational(...) then taylor(...).
Series normal_form_taylor(const GiNaC::ex& e, int n);

/// phi_j(w V) as a series: (-w)^k / (2k+j)!.
Series phi_series(int j, const Qs& w, int n);

/// Digits beyond which decimals gain nothing: the generator certifies |residual| <= 1e-45.
inline constexpr int kCertifiedDigits = 48;

/// One method read back from generated/ (its emitted closed forms, nodes and weights).
struct Method {
  std::string name;
  int s = 0, order = 0;
  bool rkn = false;
  std::string limit;  ///< name of the V -> 0 limit (an rkn table), empty if none is emitted
  std::vector<Qs> c, d;
  std::vector<std::string> names;   ///< b1..bs, bbar1..bbars, abar11, abar21, abar22, ...
  std::vector<std::string> closed;  ///< emitted closed forms (GiNaC syntax), same order
  /// 0: every number is exact (rationals and square roots). Otherwise the most significant digits
  /// of a decimal literal in the table (its precision): such a method meets its conditions to
  /// within tolerance() only.
  int digits = 0;
  int index(const std::string& coefficient) const;  ///< throws if unknown
  /// 0 for exact methods, 10^(3 - min(digits, kCertifiedDigits)) for decimal ones.
  GiNaC::numeric tolerance() const;
  /// |r| <= tolerance() (r == 0 for exact methods).
  bool negligible(const Qs& r) const;
};
std::vector<std::string> coefficient_names(int s);
/// Every method of the tables that is not an RKN limit (implicit and explicit ERKN) and has plain
/// kicks, in table order. The conditions here are the paper's, whose stages kick with grad U
/// alone; the modified kicks' trees are certified by the generator (certify.hpp) and tested in
/// tests/generator/modified_kick_test.cpp.
std::vector<Method> erkn_methods();
/// Any method of the table (ERKN or RKN limit) by name.
Method find_method(const std::string& name);
/// The methods of the paper (paper_series.hpp), read from the tables; throws if one is missing.
std::vector<Method> paper_methods();

/// A condition on the coefficients, written with the symbols b_i, bbar_i, abar_ij, v and phi.
struct Condition {
  std::string name;  ///< e.g. "(g) line 1, i = 2", "(f) b^T c^2 = 2 phi3"
  GiNaC::ex residual;
  /// Powers V^0..V^(terms-1) must vanish; kIdentity: the residual must vanish identically.
  int terms;
};
inline constexpr int kIdentity = 1 << 20;
/// A method with decimal coefficients meets an identity to within its tolerance through V^7.
inline constexpr int kDecimalIdentityTerms = 8;

/// Theorem 2, eq. (g): lines 1-2 per stage, line 3 for j < i.
std::vector<Condition> symplectic_conditions(const Method& m);
/// Theorem 1, eq. (f): trees up to order 4, each to the power of V the claimed order requires;
/// the trees with an abar-edge at V^0 only (their higher powers: edge_failures).
std::vector<Condition> order_conditions(const Method& m);

/// The same trees with rho <= order, each at V^0 only, with the classical RKN right-hand sides
/// of Hairer-Norsett-Wanner (Table II.14.3) instead of rho!/gamma * phi_rho(0).
std::vector<Condition> classical_rkn_conditions(const Method& m);
/// The paper's free choices that fix the diagonal abar_ii (Section 3, from paper_series.hpp), as
/// equalities in V; throws for a method that is not the paper's.
std::vector<Condition> defining_conditions(const Method& m);
/// Tree sums of eq. (f) in the symbols: b^T c^k, bbar^T c^k, b^T A e, bbar^T A e, b^T C A e,
/// b^T A c.
GiNaC::ex tree_sum(const Method& m, const std::string& tree);

/// Coefficient series of a method (one Series per coefficient, table order).
std::vector<Series> emitted_series(const Method& m, int n);

/// A condition that fails: its name and the lowest power of V at which it fails.
struct Failure {
  std::string condition;
  int power;  ///< -1: not identically zero (exact check)
  std::string value;
};
std::string to_string(const std::vector<Failure>& f);

/// A tree of eq. (f) with one abar-edge (b^T A e, bbar^T A e, b^T C A e, b^T A c). The root's
/// weight b_i(V) or bbar_i(V) and the edge's abar_ij(W) act on either side of the Jacobian of
/// grad U, which does not commute with M: the condition holds power by power in two matrices,
/// V^j W^k, against the weight of the variation-of-constants formula,
///   int_0^1 w((1-z)^2 V) z^p  int_0^z (z-u) phi1((z-u)^2 W) u^q du dz,
/// w = phi0 (b) or (1-z) phi1 (bbar). At V^0 W^0 this is rho!/gamma phi_rho(0); the paper's
/// rho!/gamma phi_rho(V) in a single V is not its restriction to W = V beyond V^0 (SEN-trees with
/// M-vertices, Wu, You, Shi & Wang 2010).
struct EdgeTree {
  const char* name;
  bool bbar;
  int root_leaves, edge_leaves;  ///< p-leaves (factors c) at the root and below the edge
  int rho;
};
std::vector<EdgeTree> edge_trees();
/// The exact [V^j W^k] weight of a tree.
Qs edge_weight(const EdgeTree& t, int j, int k);
/// Every V^j W^k with rho + 2(j + k) <= order (b) or rho + 1 + 2(j + k) <= order (bbar) that fails
/// (power = j + k).
std::vector<Failure> edge_failures(const Method& m, const std::vector<Series>& coefficients);

/// Evaluates each condition as a series in V from coefficient series (n terms each; a condition
/// is checked at V^0..V^(min(terms, n)-1)).
std::vector<Failure> series_failures(const std::vector<Condition>& conditions, const Method& m,
                                     const std::vector<Series>& coefficients);
/// Checks each condition exactly: every coefficient is to_rational(parse(closed form)). A method
/// with decimal coefficients: as series of the closed forms through V^7, to within its tolerance.
std::vector<Failure> exact_failures(const std::vector<Condition>& conditions, const Method& m);

/// The trigonometric normal form of an expression in the method's symbols (coefficients from
/// the closed forms, c_i and d_i as numbers).
gen::Rational exact(const GiNaC::ex& e, const Method& m);
bool identically_equal(const gen::Rational& x, const gen::Rational& y);

/// Truncated series arithmetic.
Series add(const Series& x, const Series& y);
Series mul(const Series& x, const Series& y);
/// Evaluates an expression in the method's symbols as a series from coefficient series.
Series eval_series(const GiNaC::ex& e, const Method& m, const std::vector<Series>& coefficients);

/// A printed Taylor coefficient that differs from the one derived from the emitted closed form.
struct Mismatch {
  std::string method, coefficient;
  int power;
  Qs printed, derived;
};
/// The printed series of a method (paper_series.hpp) as exact numbers, in table order: one Series
/// of V^0..V^3 per coefficient. Throws if the paper does not print every coefficient.
std::vector<Series> printed_series(const Method& m);
/// Compares the printed V^0..V^3 with `derived` (table order, at least 4 terms each).
std::vector<Mismatch> paper_mismatches(const Method& m, const std::vector<Series>& derived);

}  // namespace erkn::symtest
