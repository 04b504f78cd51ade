// Trigonometric normal form. With x = sqrt(v), every coefficient function of these methods is a
// finite sum  sum K * x^k * cos(w x)  or  K * x^k * sin(w x)  with K, w in Q(sqrt(s)), w >= 0, or a
// quotient of two such sums. Products reduce by the product-to-sum rules, so the form is
// canonical and an identity such as phi0(V)^2 + V phi1(V)^2 = 1 (det of eq. (g)) is checked
// exactly, by comparing terms. Printed back, x^(2m) cos(w x) = v^m phi0(w^2 v) and
// x^(2m-1) sin(w x) = w v^m phi1(w^2 v): closed forms in phi-functions of scalar multiples of v.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "qs.hpp"

namespace erkn::gen {

/// One term K * v^m * phi_e(w * v), e in {0, 1}, the printed form of a trig term.
struct PhiTerm {
  Qs K;
  int m;
  int e;
  Qs w;
};

class TrigPoly {
 public:
  enum Kind { kCos = 0, kSin = 1 };
  struct Key {
    int xpow;
    Kind kind;
    Qs omega;
    bool operator==(const Key& o) const {
      return xpow == o.xpow && kind == o.kind && omega == o.omega;
    }
    bool operator<(const Key& o) const {
      return std::tie(xpow, kind) < std::tie(o.xpow, o.kind) ||
             (std::tie(xpow, kind) == std::tie(o.xpow, o.kind) && omega < o.omega);
    }
  };

  TrigPoly() = default;
  TrigPoly(const Qs& constant);  // NOLINT
  /// x^xpow * cos(omega x) or x^xpow * sin(omega x), canonicalised (omega >= 0).
  static TrigPoly term(int xpow, Kind kind, const Qs& omega, const Qs& coef = Qs(1));
  /// phi0(omega^2 v) = cos(omega x) and phi1(omega^2 v) = sin(omega x)/(omega x).
  static TrigPoly phi0(const Qs& omega) { return term(0, kCos, omega); }
  static TrigPoly phi1(const Qs& omega);
  static TrigPoly v() { return term(2, kCos, Qs(0)); }

  bool is_zero() const { return terms_.empty(); }
  const std::map<Key, Qs>& terms() const { return terms_; }
  int min_xpow() const;
  /// The constant c if this is c (no x, no trig), for dividing.
  bool is_constant() const;
  TrigPoly shifted(int dxpow) const;  ///< multiplied by x^dxpow
  TrigPoly derivative() const;        ///< d/dx

  /// Laurent coefficients of x^lo .. x^hi.
  std::vector<Qs> series(int lo, int hi) const;

  /// The printed form; throws if a term is odd in x (not a function of v).
  std::vector<PhiTerm> phi_terms() const;
  std::string to_string() const;  ///< GiNaC syntax in v and phi(e, w*v)

  friend TrigPoly operator+(const TrigPoly& p, const TrigPoly& q);
  friend TrigPoly operator-(const TrigPoly& p, const TrigPoly& q);
  friend TrigPoly operator*(const TrigPoly& p, const TrigPoly& q);
  friend TrigPoly operator*(const Qs& c, const TrigPoly& p);

 private:
  void add(int xpow, Kind kind, Qs omega, Qs coef);
  std::map<Key, Qs> terms_;
};

/// A TrigPoly with its constants rounded once, for evaluation at many points.
class TrigEval {
 public:
  TrigEval(const TrigPoly& p, int digits);
  double operator()(double x) const;
  GiNaC::numeric operator()(const GiNaC::numeric& x) const;  ///< in `digits` digits
  /// Sum of |term| at x: the scale against which cancellation is measured.
  double magnitude(double x) const;

 private:
  struct Term {
    int xpow;
    bool cos;
    double w, c;
    GiNaC::numeric wn, cn;
  };
  std::vector<Term> terms_;
  int digits_;
};

/// num / den. Kept as a pair: quotients are never expanded further than the method needs.
struct Rational {
  TrigPoly num, den = TrigPoly(Qs(1));
  /// A TrigPoly if den is a constant times a power of x, else throws.
  bool is_poly() const;
  TrigPoly as_poly() const;
  /// num/den with a monic den (first term in TrigPoly order has coefficient 1): GiNaC's normal()
  /// fixes sign and scale by hash order, which varies from run to run.
  Rational monic() const;
  /// num and den multiplied by the power of v that makes the lowest power of v in either v^0.
  Rational cleared() const;
  friend Rational operator+(const Rational& p, const Rational& q);
  friend Rational operator*(const Rational& p, const Rational& q);
  Rational inverse() const { return {den, num}; }
};

/// phi_j(omega^2 v) in normal form, by phi_j(y) = (1/(j-2)! - phi_{j-2}(y)) / y for j >= 2.
Rational phi_trig(int j, const Qs& omega);

/// Exact Taylor coefficients of v^0 .. v^(n-1) of num/den (a removable 0/0 at v = 0 is fine).
std::vector<Qs> taylor(const Rational& r, int n);

}  // namespace erkn::gen
