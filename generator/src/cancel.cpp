#include "cancel.hpp"

#include <stdexcept>

using namespace GiNaC;

namespace erkn::gen {
namespace {

struct Vars {
  symbol x{"x"}, C{"C"}, S{"S"}, r{"r"};  ///< r stands for sqrt(s), the field's radicand
  long L = 1;                             ///< every frequency is n / L
  int s = 0;
};

/// T_n(C) for kind cos, U_(n-1)(C) (the cofactor of S) for kind sin.
ex chebyshev(bool cos, long n, const ex& C) {
  if (n == 0) return cos ? ex(1) : ex(0);
  ex prev = 1, cur = cos ? C : 2 * C;  // T_0, T_1 or U_0, U_1
  if (!cos) --n;
  for (long k = 1; k < n; ++k) {
    ex next = expand(2 * C * cur - prev);
    prev = cur, cur = next;
  }
  return n == 0 ? prev : cur;
}

/// Whether every frequency is rational and every coefficient exact; sets L and s.
bool representable(const TrigPoly& p, Vars& v) {
  for (const auto& [k, c] : p.terms()) {
    if (k.omega.is_approx() || !k.omega.b().is_zero() || c.is_approx()) return false;
    if (!c.b().is_zero()) {
      if (v.s != 0 && v.s != c.radicand()) return false;
      v.s = c.radicand();
    }
    v.L = lcm(numeric(v.L), k.omega.a().denom()).to_long();
  }
  return true;
}

/// p * x^shift as A + S B; returns {A, B}.
std::pair<ex, ex> to_poly(const TrigPoly& p, int shift, const Vars& v) {
  ex A = 0, B = 0;
  for (const auto& [k, c] : p.terms()) {
    ex K = c.a() + c.b() * v.r;
    long n = (k.omega.a() * v.L).to_long();
    ex term = K * pow(v.x, k.xpow + shift) * chebyshev(k.kind == TrigPoly::kCos, n, v.C);
    (k.kind == TrigPoly::kCos ? A : B) += term;
  }
  return {expand(A), expand(B)};
}

/// A polynomial in x, C, S, r back to a trig polynomial (products reduce to sums).
TrigPoly to_trig(const ex& e, const Vars& v) {
  TrigPoly out;
  ex sum = expand(e);
  for (size_t i = 0; i < (is_a<add>(sum) ? sum.nops() : 1); ++i) {
    ex t = is_a<add>(sum) ? sum.op(i) : sum;
    int rdeg = t.degree(v.r);
    numeric coef = ex_to<numeric>(t.subs(lst{v.x == 1, v.C == 1, v.S == 1, v.r == 1}));
    numeric rpow = rdeg < 2 ? numeric(1) : numeric(v.s).power(rdeg / 2);
    Qs K = rdeg % 2 ? Qs(0, coef * rpow, v.s) : Qs(coef * rpow);
    TrigPoly term(K);
    for (int k = 0; k < t.degree(v.C); ++k)
      term = term * TrigPoly::term(0, TrigPoly::kCos, Qs(numeric(1, v.L)));
    for (int k = 0; k < t.degree(v.S); ++k)
      term = term * TrigPoly::term(0, TrigPoly::kSin, Qs(numeric(1, v.L)));
    out = out + term.shifted(t.degree(v.x));
  }
  return out;
}

/// Whether p is odd in x (then it is not a function of v = x^2).
bool odd(const TrigPoly& p) {
  if (p.is_zero()) return false;
  const auto& k = p.terms().begin()->first;
  return ((k.xpow % 2 + 2) % 2 == 1) == (k.kind == TrigPoly::kCos);
}

}  // namespace

Rational cancel_common(const Rational& r) {
  Vars v;
  if (r.num.is_zero() || !representable(r.num, v) || !representable(r.den, v)) return r;
  const int shift = -std::min(r.num.min_xpow(), r.den.min_xpow());
  auto [An, Bn] = to_poly(r.num, shift, v);
  auto [Ad, Bd] = to_poly(r.den, shift, v);
  ex g = gcd(gcd(An, Bn), gcd(Ad, Bd));
  if (g.degree(v.C) == 0) {
    if (!An.is_zero() || !Ad.is_zero()) return r;
    // num = S Bn and den = S Bd: only the factor S = sin(x/L) is common.
    return {to_trig(Bn, v), to_trig(Bd, v)};
  }
  g = expand(g / pow(v.x, g.ldegree(v.x)));  // powers of x stay: they set the series at v = 0
  ex parts[4] = {An, Bn, Ad, Bd};
  for (ex& p : parts)
    if (!divide(p, g, p)) throw std::logic_error("cancel_common: gcd does not divide");
  Rational out{to_trig(parts[0] + v.S * parts[1], v), to_trig(parts[2] + v.S * parts[3], v)};
  if (odd(out.den)) out = {out.num.shifted(1), out.den.shifted(1)};
  return out;
}

}  // namespace erkn::gen
