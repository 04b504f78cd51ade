// The adapter to the ERKN runtime: every method of erkn::Method::all() as an ex::Solver.
#include <erkn/integrator.hpp>
#include <erkn/method.hpp>
#include <erkn/stability.hpp>

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

  RunResult run(const Problem& pr, double h, long steps, const Observer* obs) const override {
    erkn::Integrator integrator(method_, erkn::problems::system(pr), h, pr.q0, pr.p0);
    for (long n = 0; n < steps; ++n) {
      integrator.step();
      if (obs) (*obs)(integrator.t(), integrator.q(), integrator.p());
    }
    const erkn::Statistics& s = integrator.statistics();
    RunResult r{integrator.q(), integrator.p(), {}};
    r.stats.grad_evals = s.gradient_evaluations;
    r.stats.stage_iterations = s.stage_iterations;
    r.stats.stage_solves = s.steps * method_.stages();
    r.stats.steps = s.steps;
    return r;
  }

 private:
  const erkn::Method& method_;
};

}  // namespace

SolverList make_erkn_solvers() {
  SolverList list;
  for (const erkn::Method& m : erkn::Method::all()) list.push_back(std::make_unique<ErknSolver>(m));
  return list;
}

}  // namespace ex
