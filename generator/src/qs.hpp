// Exact numbers a + b*sqrt(s) of the quadratic field Q(sqrt(s)), s a square-free integer
// (s = 0: the rationals). Every constant of the paper's methods lives in such a field:
// SERKN2s4 in Q(sqrt(3)), SERKN3s4(1,2) in Q(sqrt(15)), the others in Q.
// Constants outside one such field (decimals of the literature, 2^(1/3), sqrt(2) with sqrt(3))
// are *approximate*: kApproxDigits-digit CLN floats, and anything computed from them is too.
// An approximate number counts as zero when |x| <= kApproxZero, so identities that hold
// exactly hold to that bound; certificates say which arithmetic they used.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace erkn::gen {

class Qs {
 public:
  static constexpr int kApproxDigits = 60;
  /// Significant digits an approximate constant is printed with (to_string): below the working
  /// precision, so that the printed digits do not depend on the order of evaluation.
  static constexpr int kPrintDigits = 50;
  static const GiNaC::numeric& approx_zero();  ///< 1e-45
  Qs() = default;
  Qs(long n) : a_(n) {}  // NOLINT: integers convert implicitly, like GiNaC::numeric
  Qs(GiNaC::numeric a, GiNaC::numeric b = 0, int s = 0);

  /// Reads an expanded GiNaC expression p + q*sqrt(s) (p, q rational); any other real
  /// constant expression becomes approximate; throws for anything else.
  static Qs from_ex(const GiNaC::ex& e);
  /// The kApproxDigits-digit value of a real constant.
  static Qs approximate(const GiNaC::ex& e);

  bool is_approx() const { return approx_; }

  const GiNaC::numeric& a() const { return a_; }
  const GiNaC::numeric& b() const { return b_; }
  int radicand() const { return s_; }

  bool is_zero() const { return approx_ ? sign() == 0 : a_.is_zero() && b_.is_zero(); }
  int sign() const;  ///< exact sign of the real number
  Qs operator-() const { return Qs(-a_, -b_, s_); }
  Qs inverse() const;
  /// The square root, when it lies in the same field (throws otherwise).
  Qs sqrt() const;

  GiNaC::ex to_ex() const;
  GiNaC::numeric to_float(int digits) const;  ///< value as a CLN float with `digits` digits
  double to_double() const;
  std::string to_string() const;  ///< GiNaC syntax, e.g. "1/2-1/10*sqrt(15)"
  /// Plain decimal rounded to `digits` significant digits, e.g. "0.1127016653792583114820735".
  std::string decimal(int digits) const;

  friend Qs operator+(const Qs& x, const Qs& y);
  friend Qs operator-(const Qs& x, const Qs& y) { return x + (-y); }
  friend Qs operator*(const Qs& x, const Qs& y);
  friend Qs operator/(const Qs& x, const Qs& y) { return x * y.inverse(); }
  friend bool operator==(const Qs& x, const Qs& y) { return (x - y).is_zero(); }
  friend bool operator<(const Qs& x, const Qs& y) { return (x - y).sign() < 0; }

 private:
  static int common_radicand(const Qs& x, const Qs& y);  ///< -1: different fields
  GiNaC::numeric value() const;                          ///< kApproxDigits-digit value
  GiNaC::numeric a_ = 0, b_ = 0;  ///< approximate: a_ is the value (a CLN float), b_ = 0
  int s_ = 0;
  bool approx_ = false;
};

}  // namespace erkn::gen
