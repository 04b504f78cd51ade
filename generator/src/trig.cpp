#include "trig.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

using GiNaC::numeric;

namespace erkn::gen {

TrigPoly::TrigPoly(const Qs& constant) { add(0, kCos, Qs(0), constant); }

TrigPoly TrigPoly::term(int xpow, Kind kind, const Qs& omega, const Qs& coef) {
  TrigPoly p;
  p.add(xpow, kind, omega, coef);
  return p;
}

TrigPoly TrigPoly::phi1(const Qs& omega) {
  if (omega.is_zero()) return TrigPoly(Qs(1));
  return term(-1, kSin, omega, omega.inverse());
}

void TrigPoly::add(int xpow, Kind kind, Qs omega, Qs coef) {
  if (omega.sign() < 0) {  // cos(-w x) = cos(w x), sin(-w x) = -sin(w x)
    omega = -omega;
    if (kind == kSin) coef = -coef;
  }
  if (coef.is_zero() || (kind == kSin && omega.is_zero())) return;
  Key k{xpow, kind, omega};
  auto [it, inserted] = terms_.try_emplace(k, coef);
  if (!inserted) {
    it->second = it->second + coef;
    if (it->second.is_zero()) terms_.erase(it);
  }
}

int TrigPoly::min_xpow() const {
  int m = 0;
  bool first = true;
  for (const auto& [k, c] : terms_) m = first ? k.xpow : std::min(m, k.xpow), first = false;
  return m;
}

bool TrigPoly::is_constant() const {
  return terms_.empty() ||
         (terms_.size() == 1 && terms_.begin()->first.xpow == 0 &&
          terms_.begin()->first.kind == kCos && terms_.begin()->first.omega.is_zero());
}

TrigPoly TrigPoly::shifted(int dxpow) const {
  TrigPoly r;
  for (const auto& [k, c] : terms_) r.add(k.xpow + dxpow, k.kind, k.omega, c);
  return r;
}

TrigPoly TrigPoly::derivative() const {
  TrigPoly r;
  for (const auto& [k, c] : terms_) {
    if (k.xpow != 0) r.add(k.xpow - 1, k.kind, k.omega, c * Qs(k.xpow));
    if (k.kind == kCos)
      r.add(k.xpow, kSin, k.omega, -(c * k.omega));
    else
      r.add(k.xpow, kCos, k.omega, c * k.omega);
  }
  return r;
}

TrigPoly operator+(const TrigPoly& p, const TrigPoly& q) {
  TrigPoly r = p;
  for (const auto& [k, c] : q.terms_) r.add(k.xpow, k.kind, k.omega, c);
  return r;
}

TrigPoly operator-(const TrigPoly& p, const TrigPoly& q) { return p + Qs(-1) * q; }

TrigPoly operator*(const Qs& c, const TrigPoly& p) {
  TrigPoly r;
  for (const auto& [k, d] : p.terms_) r.add(k.xpow, k.kind, k.omega, c * d);
  return r;
}

TrigPoly operator*(const TrigPoly& p, const TrigPoly& q) {
  using K = TrigPoly::Kind;
  TrigPoly r;
  const Qs half(numeric(1, 2));
  for (const auto& [a, ca] : p.terms_)
    for (const auto& [b, cb] : q.terms_) {
      int x = a.xpow + b.xpow;
      Qs c = half * ca * cb, s = a.omega + b.omega, d = a.omega - b.omega;
      if (a.kind == K::kCos && b.kind == K::kCos) {  // cos A cos B = (cos(A-B) + cos(A+B))/2
        r.add(x, K::kCos, d, c), r.add(x, K::kCos, s, c);
      } else if (a.kind == K::kSin && b.kind == K::kSin) {  // sin A sin B = (cos(A-B) - cos(A+B))/2
        r.add(x, K::kCos, d, c), r.add(x, K::kCos, s, -c);
      } else if (a.kind == K::kSin) {  // sin A cos B = (sin(A+B) + sin(A-B))/2
        r.add(x, K::kSin, s, c), r.add(x, K::kSin, d, c);
      } else {  // cos A sin B = (sin(A+B) - sin(A-B))/2
        r.add(x, K::kSin, s, c), r.add(x, K::kSin, d, -c);
      }
    }
  return r;
}

std::vector<Qs> TrigPoly::series(int lo, int hi) const {
  std::vector<Qs> out(std::max(0, hi - lo + 1));
  for (const auto& [k, c] : terms_) {
    // cos(w x) = sum (-1)^m w^(2m) x^(2m) / (2m)!,  sin(w x) = sum (-1)^m w^(2m+1) x^(2m+1)/(2m+1)!
    Qs wpow = k.kind == kCos ? Qs(1) : k.omega;
    numeric fact = 1;
    for (int n = (k.kind == kCos ? 0 : 1);; n += 2) {
      int p = n + k.xpow;
      if (p > hi) break;
      if (n > 1) fact *= numeric(n) * numeric(n - 1);
      if (p >= lo) out[p - lo] = out[p - lo] + Qs(((n / 2) % 2 ? -1 : 1) / fact) * c * wpow;
      wpow = wpow * k.omega * k.omega;
      if (wpow.is_zero()) break;
    }
  }
  return out;
}

TrigEval::TrigEval(const TrigPoly& p, int digits) : digits_(digits) {
  for (const auto& [k, c] : p.terms())
    terms_.push_back({k.xpow, k.kind == TrigPoly::kCos, k.omega.to_double(), c.to_double(),
                      k.omega.to_float(digits), c.to_float(digits)});
}

numeric TrigEval::operator()(const numeric& x) const {
  long saved = GiNaC::Digits;
  GiNaC::Digits = digits_;
  numeric sum = 0;
  for (const Term& t : terms_)
    sum += t.cn * x.power(t.xpow) * (t.cos ? GiNaC::cos(t.wn * x) : GiNaC::sin(t.wn * x));
  GiNaC::Digits = saved;
  return sum;
}

double TrigEval::operator()(double x) const {
  double sum = 0;
  for (const Term& t : terms_)
    sum += t.c * std::pow(x, t.xpow) * (t.cos ? std::cos(t.w * x) : std::sin(t.w * x));
  return sum;
}

double TrigEval::magnitude(double x) const {
  double sum = 0;
  for (const Term& t : terms_)
    sum += std::abs(t.c * std::pow(x, t.xpow) * (t.cos ? std::cos(t.w * x) : std::sin(t.w * x)));
  return sum;
}

std::vector<PhiTerm> TrigPoly::phi_terms() const {
  std::vector<PhiTerm> out;
  for (const auto& [k, c] : terms_) {
    bool odd = (k.xpow % 2 + 2) % 2 == 1;
    if ((k.kind == kCos) == odd) throw std::logic_error("trig term odd in x: not a function of v");
    Qs w = k.omega * k.omega;
    if (k.kind == kCos)
      out.push_back({c, k.xpow / 2, 0, w});
    else  // x^(2m-1) sin(w x) = w v^m phi1(w^2 v)
      out.push_back({c * k.omega, (k.xpow + 1) / 2, 1, w});
  }
  return out;
}

std::string TrigPoly::to_string() const {
  if (terms_.empty()) return "0";
  std::ostringstream os;
  bool first = true;
  for (const PhiTerm& t : phi_terms()) {
    if (!first) os << "+";
    first = false;
    os << "(" << t.K.to_string() << ")";
    if (t.m != 0) os << "*v^(" << t.m << ")";
    if (!(t.e == 0 && t.w.is_zero()))
      os << "*phi(" << t.e << ","
         << (t.w == Qs(1) ? std::string("v") : "(" + t.w.to_string() + ")*v") << ")";
  }
  return os.str();
}

bool Rational::is_poly() const {
  return den.terms().size() == 1 && den.terms().begin()->first.kind == TrigPoly::kCos &&
         den.terms().begin()->first.omega.is_zero();
}

TrigPoly Rational::as_poly() const {
  if (!is_poly()) throw std::logic_error("Rational::as_poly: denominator is not a monomial");
  const auto& [k, c] = *den.terms().begin();
  return c.inverse() * num.shifted(-k.xpow);
}

Rational Rational::monic() const {
  if (den.is_zero()) throw std::domain_error("Rational with zero denominator");
  Qs lead = den.terms().begin()->second.inverse();
  return {lead * num, lead * den};
}

Rational Rational::cleared() const {
  // Lowest power of v in the phi form (x^(2m) cos = v^m phi0, x^(2m-1) sin = w v^m phi1).
  auto min_m = [](const TrigPoly& p) {
    int m = 0;
    bool first = true;
    for (const PhiTerm& t : p.phi_terms()) m = first ? t.m : std::min(m, t.m), first = false;
    return m;
  };
  int m = num.is_zero() ? min_m(den) : std::min(min_m(num), min_m(den));
  return {num.shifted(-2 * m), den.shifted(-2 * m)};
}

Rational operator+(const Rational& p, const Rational& q) {
  if (p.den.terms() == q.den.terms()) return {p.num + q.num, p.den};
  return {p.num * q.den + q.num * p.den, p.den * q.den};
}

Rational operator*(const Rational& p, const Rational& q) { return {p.num * q.num, p.den * q.den}; }

Rational phi_trig(int j, const Qs& omega) {
  if (j == 0) return {TrigPoly::phi0(omega)};
  if (j == 1) return {TrigPoly::phi1(omega)};
  if (omega.is_zero()) {
    numeric f = 1;
    for (int i = 2; i <= j; ++i) f *= i;
    return {TrigPoly(Qs(1 / f))};
  }
  numeric f = 1;
  for (int i = 2; i <= j - 2; ++i) f *= i;
  Rational lower = phi_trig(j - 2, omega);
  // (1/(j-2)! - phi_{j-2}) / (omega^2 x^2)
  TrigPoly num = TrigPoly(Qs(1 / f)) * lower.den - lower.num;
  return {num, TrigPoly::term(2, TrigPoly::kCos, Qs(0), omega * omega) * lower.den};
}

std::vector<Qs> taylor(const Rational& r, int n) {
  // Laurent series in x of num and den; quotient by long division; even powers are v^k.
  int ld = r.den.min_xpow();
  std::vector<Qs> den = r.den.series(ld, ld + 4 * n + 40);
  int shift = 0;
  while (shift < int(den.size()) && den[shift].is_zero()) ++shift;
  if (shift == int(den.size())) throw std::domain_error("taylor: denominator vanishes identically");
  int lead = ld + shift;  // den = x^lead (den[shift] + ...)
  int lo = lead;          // quotient q_k multiplies x^k; we need k = 0 .. 2n-2, num from x^lead
  std::vector<Qs> num =
      r.num.series(std::min(lo, r.num.is_zero() ? lo : r.num.min_xpow()), lead + 2 * n);
  int nlo = std::min(lo, r.num.is_zero() ? lo : r.num.min_xpow());
  // q(x) = num/den; coefficients of x^(p) for p from nlo - lead to 2n - 1.
  int qlo = nlo - lead, qn = 2 * n - qlo;
  std::vector<Qs> q(qn);
  Qs inv = den[shift].inverse();
  for (int i = 0; i < qn; ++i) {
    Qs acc = num[i];
    if (shift + i >= int(den.size()))
      throw std::logic_error("taylor: denominator series too short");
    for (int j = 1; j <= i; ++j) acc = acc - q[i - j] * den[shift + j];
    q[i] = acc * inv;
  }
  std::vector<Qs> out(n);
  for (int i = 0; i < qn; ++i) {
    int p = qlo + i;
    if (p < 0 || p % 2) {
      if (!q[i].is_zero())
        throw std::domain_error("taylor: not a power series in v (pole or odd term)");
      continue;
    }
    if (p / 2 < n) out[p / 2] = q[i];
  }
  return out;
}

}  // namespace erkn::gen
