#include "qs.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

using GiNaC::ex;
using GiNaC::numeric;

namespace erkn::gen {
namespace {

// Runs f with GiNaC::Digits = Qs::kApproxDigits.
template <class F>
numeric with_digits(F f) {
  long saved = GiNaC::Digits;
  GiNaC::Digits = Qs::kApproxDigits;
  numeric r = f();
  GiNaC::Digits = saved;
  return r;
}

Qs approx_of(const numeric& x) { return Qs::approximate(x); }

}  // namespace

const numeric& Qs::approx_zero() {
  static const numeric z = numeric(1) / numeric(10).power(45);
  return z;
}

Qs::Qs(numeric a, numeric b, int s) : a_(a), b_(b), s_(s) {
  if (!a_.is_rational() || !b_.is_rational()) {
    *this = approximate(a_ + b_ * GiNaC::sqrt(numeric(s)));
    return;
  }
  if (b_.is_zero()) s_ = 0;
  if (s_ == 0) b_ = 0;
}

Qs Qs::approximate(const ex& e) {
  ex f = with_digits([&] {
    ex v = GiNaC::evalf(e);
    if (!GiNaC::is_a<numeric>(v) || !GiNaC::ex_to<numeric>(v).is_real())
      throw std::invalid_argument("not a real constant");
    return GiNaC::ex_to<numeric>(v);
  });
  Qs r;
  r.a_ = GiNaC::ex_to<numeric>(f);
  r.approx_ = true;
  return r;
}

numeric Qs::value() const {
  if (approx_) return a_;
  return with_digits([&] { return GiNaC::ex_to<numeric>(GiNaC::evalf(to_ex())); });
}

int Qs::common_radicand(const Qs& x, const Qs& y) {
  if (x.approx_ || y.approx_ || (x.s_ && y.s_ && x.s_ != y.s_)) return -1;
  return x.s_ ? x.s_ : y.s_;
}

Qs operator+(const Qs& x, const Qs& y) {
  int s = Qs::common_radicand(x, y);
  if (s < 0) return approx_of(with_digits([&] { return x.value() + y.value(); }));
  return Qs(x.a_ + y.a_, x.b_ + y.b_, s);
}

Qs operator*(const Qs& x, const Qs& y) {
  int s = Qs::common_radicand(x, y);
  if (s < 0) return approx_of(with_digits([&] { return x.value() * y.value(); }));
  return Qs(x.a_ * y.a_ + x.b_ * y.b_ * s, x.a_ * y.b_ + x.b_ * y.a_, s);
}

Qs Qs::inverse() const {
  if (approx_) {
    if (a_.is_zero()) throw std::domain_error("Qs: division by (approximate) zero");
    return approx_of(with_digits([&] { return numeric(1) / a_; }));
  }
  numeric n = a_ * a_ - b_ * b_ * s_;  // (a + b r)(a - b r); nonzero for square-free s
  if (n.is_zero()) throw std::domain_error("Qs: division by zero");
  return Qs(a_ / n, -b_ / n, s_);
}

int Qs::sign() const {
  if (approx_) return GiNaC::abs(a_) <= approx_zero() ? 0 : a_.csgn();
  int sa = a_.csgn(), sb = b_.csgn();
  if (sb == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  // a and b*sqrt(s) have opposite signs: compare a^2 with b^2 s.
  numeric d = a_ * a_ - b_ * b_ * s_;
  return d.is_zero() ? 0 : (d.is_positive() ? sa : sb);
}

Qs Qs::sqrt() const {
  if (sign() < 0) throw std::domain_error("Qs::sqrt of a negative number");
  if (is_zero()) return Qs();
  if (approx_) return approx_of(with_digits([&] { return GiNaC::sqrt(a_); }));
  if (s_ == 0) {
    numeric r = GiNaC::sqrt(a_);
    if (r.is_rational()) return Qs(r);
    // sqrt(p/q) = sqrt(p q)/q: write p q = k^2 m with m square-free, by trial division up to
    // kTrial. If p q may keep a square factor beyond that, or m does not fit the radicand (an
    // int), the root is not a number of a small quadratic field: approximate it.
    constexpr long kTrial = 100000;
    numeric n = a_.numer() * a_.denom(), k = 1;
    for (long f = 2; f <= kTrial && numeric(f * f) <= n; ++f)
      while (GiNaC::irem(n, numeric(f * f)).is_zero()) n = n / (f * f), k = k * f;
    if (n >= numeric(kTrial) * kTrial || n > std::numeric_limits<int>::max())
      return approx_of(with_digits([&] { return GiNaC::sqrt(a_); }));
    return Qs(0, k / a_.denom(), n.to_int());
  }
  // (p + q r)^2 = a + b r  =>  p^2 + s q^2 = a, 2 p q = b; p^2 is a root of t^2 - a t + b^2 s/4.
  numeric disc = a_ * a_ - b_ * b_ * s_;
  numeric sd = GiNaC::sqrt(disc);
  if (!sd.is_rational()) throw std::domain_error("Qs::sqrt: not a square in Q(sqrt(s))");
  for (numeric p2 : {(a_ + sd) / 2, (a_ - sd) / 2}) {
    numeric p = GiNaC::sqrt(p2);
    if (!p.is_rational() || p.is_zero()) continue;
    Qs r(p, b_ / (2 * p), s_);
    if (r.sign() < 0) r = -r;
    if (r * r == *this) return r;
  }
  throw std::domain_error("Qs::sqrt: not a square in Q(sqrt(s))");
}

Qs Qs::from_ex(const ex& e0) {
  ex e = GiNaC::expand(e0);
  auto term = [](const ex& t) -> Qs {
    if (GiNaC::is_a<numeric>(t)) return Qs(GiNaC::ex_to<numeric>(t));
    auto radical = [](const ex& p) -> Qs {
      if (GiNaC::is_a<GiNaC::power>(p) && GiNaC::is_a<numeric>(p.op(0)) && p.op(1) == ex(1) / 2)
        return Qs(0, 1, GiNaC::ex_to<numeric>(p.op(0)).to_int());
      if (GiNaC::is_a<GiNaC::power>(p) && GiNaC::is_a<numeric>(p.op(0)) && p.op(1) == ex(-1) / 2) {
        int s = GiNaC::ex_to<numeric>(p.op(0)).to_int();
        return Qs(0, numeric(1, s), s);
      }
      throw std::invalid_argument("not in Q(sqrt(s))");
    };
    if (GiNaC::is_a<GiNaC::mul>(t)) {
      Qs r(1);
      for (size_t i = 0; i < t.nops(); ++i)
        r = r *
            (GiNaC::is_a<numeric>(t.op(i)) ? Qs(GiNaC::ex_to<numeric>(t.op(i))) : radical(t.op(i)));
      return r;
    }
    return radical(t);
  };
  try {
    if (!GiNaC::is_a<GiNaC::add>(e)) return term(e);
    Qs r;
    for (size_t i = 0; i < e.nops(); ++i) r = r + term(e.op(i));
    return r;
  } catch (const std::invalid_argument&) {
    try {
      return approximate(e0);
    } catch (const std::invalid_argument&) {
      std::ostringstream os;
      os << e0;
      throw std::invalid_argument("expected a real constant: " + os.str());
    }
  }
}

ex Qs::to_ex() const { return approx_ ? ex(a_) : a_ + b_ * GiNaC::sqrt(ex(s_)); }

numeric Qs::to_float(int digits) const {
  long saved = GiNaC::Digits;
  GiNaC::Digits = digits;
  numeric r = GiNaC::ex_to<numeric>(GiNaC::evalf(to_ex()));
  GiNaC::Digits = saved;
  return r;
}

double Qs::to_double() const { return to_float(40).to_double(); }

namespace {
// x to `digits` significant digits in plain decimal notation. The digits of a kApproxDigits-digit
// float beyond that carry the roundoff of its computation, which depends on the order GiNaC
// evaluates terms in; printing them would make regeneration irreproducible.
std::string rounded(const numeric& x, int digits) {
  std::ostringstream os;
  os << GiNaC::abs(x);
  std::string t = os.str(), mantissa;
  long exponent = 0;  // value = 0.mantissa * 10^exponent
  const size_t e = t.find_first_of("eE");
  if (e != std::string::npos) exponent = std::stol(t.substr(e + 1)), t = t.substr(0, e);
  const size_t dot = t.find('.');
  exponent += long(dot == std::string::npos ? t.size() : dot);
  for (char ch : t)
    if (ch != '.') mantissa += ch;
  const size_t first = mantissa.find_first_not_of('0');
  if (first == std::string::npos) return "0";
  exponent -= long(first);
  mantissa = mantissa.substr(first);
  if (mantissa.size() > size_t(digits)) {
    const bool up = mantissa[digits] >= '5';
    mantissa.resize(digits);
    for (long i = digits - 1; up && i >= -1; --i) {
      if (i < 0) {
        mantissa.insert(mantissa.begin(), '1'), ++exponent, mantissa.pop_back();
        break;
      }
      if (mantissa[i] == '9') {
        mantissa[i] = '0';
        continue;
      }
      ++mantissa[i];
      break;
    }
  }
  while (mantissa.size() > 1 && mantissa.back() == '0') mantissa.pop_back();
  std::string out = x.is_negative() ? "-" : "";
  if (exponent <= 0)
    out += "0." + std::string(size_t(-exponent), '0') + mantissa;
  else if (size_t(exponent) >= mantissa.size())
    out += mantissa + std::string(size_t(exponent) - mantissa.size(), '0');
  else
    out += mantissa.substr(0, size_t(exponent)) + "." + mantissa.substr(size_t(exponent));
  return out;
}
}  // namespace

std::string Qs::decimal(int digits) const { return rounded(to_float(digits + 15), digits); }

std::string Qs::to_string() const {
  std::ostringstream os;
  if (approx_) return rounded(a_, kPrintDigits);
  if (b_.is_zero()) {
    os << a_;
    return os.str();
  }
  if (!a_.is_zero()) os << a_ << (b_.is_positive() ? "+" : "");
  if (b_ == -1)
    os << "-";
  else if (b_ != 1)
    os << b_ << "*";
  os << "sqrt(" << s_ << ")";
  return os.str();
}

}  // namespace erkn::gen
