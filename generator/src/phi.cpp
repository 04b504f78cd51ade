#include "phi.hpp"

#include <cmath>
#include <stdexcept>

using namespace GiNaC;

namespace erkn::gen {
namespace {

// The index j; evalf() hands it over as a float (0.0 for 0), which is fine if integral.
int order_of(const ex& j) {
  if (is_a<numeric>(j) && ex_to<numeric>(j).is_real()) {
    double x = ex_to<numeric>(j).to_double();
    if (x >= 0 && x == std::floor(x) && x < 1000) return int(x);
  }
  throw std::invalid_argument("phi(j, x): j must be a non-negative integer");
}

ex phi_eval(const ex& j, const ex& x) {
  if (x.is_zero()) return 1 / factorial(order_of(j));
  return phi(j, x).hold();
}

// phi_j(x) for numeric x: the series while |x| is small (no cancellation), else the closed
// forms phi0 = cos(sqrt x), phi1 = sin(sqrt x)/sqrt x and phi_{j+2} = (1/j! - phi_j)/x.
ex phi_evalf(const ex& j, const ex& x) {
  if (!is_a<numeric>(x)) return phi(j, x).hold();
  int n = order_of(j);
  numeric y = ex_to<numeric>(x);
  if (abs(y) < 1) {
    numeric sum = 0, term = numeric(1) / factorial(numeric(n));
    for (int k = 0; k < 400 && term != 0; ++k) {
      sum += term;
      term = -term * y / ((2 * k + n + 1) * (2 * k + n + 2));
      if (abs(term) < abs(sum) * numeric(10).power(-long(Digits) - 5)) break;
    }
    return sum;
  }
  numeric r = sqrt(y);
  numeric p0 = cos(r), p1 = sin(r) / r;
  if (n == 0) return p0;
  if (n == 1) return p1;
  return (numeric(1) / factorial(numeric(n - 2)) - ex_to<numeric>(phi_evalf(n - 2, y))) / y;
}

// d/dx phi_j(x) = (j phi_{j+2}(x) - phi_{j+1}(x)) / 2, from the series termwise.
ex phi_deriv(const ex& j, const ex& x, unsigned param) {
  if (param == 0) throw std::invalid_argument("phi: no derivative in j");
  return (j * phi(j + 2, x) - phi(j + 1, x)) / 2;
}

ex phi_series(const ex& j, const ex& x, const relational& rel, int order, unsigned options) {
  int n = order_of(j);
  ex x0 = x.subs(rel, subs_options::no_pattern);
  if (!x0.is_zero()) throw do_taylor();  // expand by derivatives
  ex sum = 0;
  for (int k = 0; k <= order; ++k) sum += pow(-1, k) * pow(x, k) / factorial(2 * k + n);
  return sum.series(rel, order, options);
}

}  // namespace

REGISTER_FUNCTION(
    phi,
    eval_func(phi_eval).evalf_func(phi_evalf).derivative_func(phi_deriv).series_func(phi_series))

parser make_parser(const symbol& v) {
  symtab table;
  table["v"] = v;
  return parser(table, true);
}

}  // namespace erkn::gen
