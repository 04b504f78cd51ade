// Runs the user's method METHOD_NAME through erkn::Method::by_name on q'' + q = -q^3 and prints
// its observed order (log2 of the error ratios at h = 0.2, 0.1, 0.05, 0.025; reference: erkn's
// SRKN14a at h = 0.0025); exits 1 unless every slope is within 0.15 of the certified order.
#include <cmath>
#include <cstdio>
#include <erkn/erkn.hpp>

namespace {

double q_at_10(const erkn::Method& m, double h) {
  erkn::System s;
  s.M = erkn::Stiffness::scalar(1.0);
  s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().cube(); };
  s.potential = [](const Eigen::VectorXd& q) { return 0.25 * q.array().pow(4).sum(); };
  Eigen::VectorXd q0(1), p0(1);
  q0 << 1.0;
  p0 << 0.0;
  erkn::Integrator run(m, s, h, q0, p0);
  run.integrate(10.0);
  return run.q()[0];
}

}  // namespace

int main() {
#ifdef METHOD_NAME
  const erkn::Method& m = erkn::Method::by_name(METHOD_NAME);
  bool listed = false;
  for (const erkn::Method& x : erkn::Method::all()) listed |= &x == &m;
  std::printf("%s: %d stages, certified order %d, listed in Method::all() (%zu methods): %s\n",
              std::string(m.name()).c_str(), m.stages(), m.order(), erkn::Method::all().size(),
              listed ? "yes" : "no");
  const double ref = q_at_10(erkn::Method::by_name("SRKN14a"), 0.0025);
  double previous = 0;
  bool ok = listed;
  for (double h : {0.2, 0.1, 0.05, 0.025}) {
    const double error = std::abs(q_at_10(m, h) - ref);
    if (previous > 0) {
      const double slope = std::log2(previous / error);
      std::printf("h = %.3f  error %.3e  observed order %.3f\n", h, error, slope);
      ok &= std::abs(slope - m.order()) <= 0.15;
    } else {
      std::printf("h = %.3f  error %.3e\n", h, error);
    }
    previous = error;
  }
  return ok ? 0 : 1;
#else
  std::printf("%zu methods\n", erkn::Method::all().size());
  return 0;
#endif
}
