// Exact numbers a + b*sqrt(s) of the quadratic field Q(sqrt(s)), s a square-free integer
// (s = 0: the rationals). Every constant of the paper's methods lives in such a field:
// SERKN2s4 in Q(sqrt(3)), SERKN3s4(1,2) in Q(sqrt(15)), the others in Q.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace erkn::gen {

class Qs {
 public:
  Qs() = default;
  Qs(long n) : a_(n) {}  // NOLINT: integers convert implicitly, like GiNaC::numeric
  Qs(GiNaC::numeric a, GiNaC::numeric b = 0, int s = 0);

  /// Reads an expanded GiNaC expression p + q*sqrt(s) (p, q rational); throws otherwise.
  static Qs from_ex(const GiNaC::ex& e);

  const GiNaC::numeric& a() const { return a_; }
  const GiNaC::numeric& b() const { return b_; }
  int radicand() const { return s_; }

  bool is_zero() const { return a_.is_zero() && b_.is_zero(); }
  int sign() const;  ///< exact sign of the real number
  Qs operator-() const { return Qs(-a_, -b_, s_); }
  Qs inverse() const;
  /// The square root, when it lies in the same field (throws otherwise).
  Qs sqrt() const;

  GiNaC::ex to_ex() const;
  GiNaC::numeric to_float(int digits) const;  ///< value as a CLN float with `digits` digits
  double to_double() const;
  std::string to_string() const;  ///< GiNaC syntax, e.g. "1/2-1/10*sqrt(15)"

  friend Qs operator+(const Qs& x, const Qs& y);
  friend Qs operator-(const Qs& x, const Qs& y) { return x + (-y); }
  friend Qs operator*(const Qs& x, const Qs& y);
  friend Qs operator/(const Qs& x, const Qs& y) { return x * y.inverse(); }
  friend bool operator==(const Qs& x, const Qs& y) { return (x - y).is_zero(); }
  friend bool operator<(const Qs& x, const Qs& y) { return (x - y).sign() < 0; }

 private:
  static int common_radicand(const Qs& x, const Qs& y);
  GiNaC::numeric a_ = 0, b_ = 0;
  int s_ = 0;
};

}  // namespace erkn::gen
