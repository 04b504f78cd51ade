// The adapter to the ERKN runtime: every method of erkn::Method::all() as an ex::Solver.
#include <algorithm>
#include <cmath>
#include <erkn/integrator.hpp>
#include <erkn/method.hpp>
#include <erkn/stability.hpp>
#include <vector>

#include "solver.hpp"

namespace ex {
namespace {

class ErknSolver : public Solver {
 public:
  explicit ErknSolver(const erkn::Method& method) : method_(method) {}
  std::string name() const override { return std::string(method_.name()); }
  Family family() const override {
    return method_.kind() == erkn::Kind::erkn ? Family::erkn : Family::rkn;
  }
  int order() const override { return method_.order(); }
  // The paper's methods are its diagonal implicit ERKN methods and their V -> 0 limits; the
  // registry marks the explicit (splitting) family, which the paper does not contain. (An implicit
  // method from another source would need a registry flag of its own: there is none yet.)
  bool from_paper() const override { return method_.from_paper(); }
  std::optional<double> first_unstable_z() const override {
    return ex::first_unstable_z([this](double z) {
      const erkn::StabilityClass c = erkn::classify(erkn::stability_matrix(method_, 0, z));
      return c == erkn::StabilityClass::unstable || c == erkn::StabilityClass::singular;
    });
  }
  bool exact_for_linear_part() const override { return method_.kind() != erkn::Kind::rkn; }
  bool is_explicit() const override { return method_.is_explicit(); }
  std::string limit_of() const override;
  // The RKN limits would have to resolve M's frequencies: left out of the grids.
  bool suits_grid() const override { return method_.kind() == erkn::Kind::erkn; }

  RunResult run(const Problem& pr, double h, long steps, const Observer* obs) const override {
    erkn::Integrator integrator(method_, erkn::problems::system(pr), h, pr.q0, pr.p0);
    if (!obs) {  // (as users run to an end: one batch, a processed method's pi once at its end)
      integrator.step(steps);
    } else {
      for (long n = 0; n < steps; ++n) {
        integrator.step();
        (*obs)(integrator.t(), integrator.q(), integrator.p());
      }
    }
    const erkn::Statistics& s = integrator.statistics();
    RunResult r{integrator.q(), integrator.p(), {}};
    r.stats.grad_evals = s.gradient_evaluations;
    r.stats.stage_iterations = s.stage_iterations;
    r.stats.stage_solves = method_.is_explicit() ? 0 : s.steps * method_.stages();
    r.stats.steps = s.steps;
    return r;
  }

 private:
  const erkn::Method& method_;
};

// b, bbar, abar and c of a and b agree at v (to 1e-14 relative).
bool same_coefficients(const erkn::Method& a, const erkn::Method& b, double v) {
  const erkn::Coefficients x = a.at(v), y = b.at(v);
  auto near = [](double p, double q) { return std::abs(p - q) <= 1e-14 * (1 + std::abs(q)); };
  for (int i = 0; i < x.s; ++i) {
    if (!near(x.c[i], y.c[i]) || !near(x.b[i], y.b[i]) || !near(x.bbar[i], y.bbar[i])) return false;
    for (int j = 0; j <= i; ++j)
      if (!near(x.abar(i, j), y.abar(i, j))) return false;
  }
  return true;
}

// Two registry methods are the same method when they are integrated the same way and their
// coefficients agree at several v (the RKN limits use only v = 0): e.g. the RKN limits of the
// pole-free variants are the paper's RKN limits, since the variants keep c, d and abar_ii(0).
bool same_method(const erkn::Method& a, const erkn::Method& b) {
  if (a.kind() != b.kind() || a.stages() != b.stages() || a.is_explicit() != b.is_explicit() ||
      !std::equal(a.modified().begin(), a.modified().end(), b.modified().begin(),
                  b.modified().end()))
    return false;
  const std::vector<double> vs =
      a.kind() == erkn::Kind::rkn ? std::vector<double>{0} : std::vector<double>{0, 0.37, 2.9};
  for (double v : vs) {
    if (a.pole_within(v, 1e-3) >= 0 || b.pole_within(v, 1e-3) >= 0) return false;
    if (!same_coefficients(a, b, v)) return false;
  }
  return true;
}

// The registry's first method identical to m, or m itself.
const erkn::Method& first_twin(const erkn::Method& m) {
  for (const erkn::Method& other : erkn::Method::all())
    if (&other == &m || same_method(other, m)) return other;
  return m;
}

std::string ErknSolver::limit_of() const {
  if (method_.kind() != erkn::Kind::rkn) return "";
  for (const erkn::Method& m : erkn::Method::all())
    if (m.kind() == erkn::Kind::erkn && m.stages() == method_.stages() &&
        m.pole_within(0, 1e-3) < 0 && same_coefficients(m, method_, 0))
      return std::string(m.name());
  return "";
}

}  // namespace

SolverList make_erkn_solvers() {
  SolverList list;
  for (const erkn::Method& m : erkn::Method::all())
    if (&first_twin(m) == &m) list.push_back(std::make_unique<ErknSolver>(m));
  return list;
}

std::vector<Twin> identical_registry_methods() {
  std::vector<Twin> twins;
  for (const erkn::Method& m : erkn::Method::all())
    if (const erkn::Method& t = first_twin(m); &t != &m)
      twins.push_back({std::string(m.name()), std::string(t.name())});
  return twins;
}

}  // namespace ex
