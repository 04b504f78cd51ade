// Boost.Odeint's symplectic RKN steppers of McLachlan, used as shipped (odeint evaluates the force
// in every stage, including the last one whose weight is 0; those evaluations are counted).
// Include order matters: odeint's Eigen support and the m4 stepper do not include what they use.
// clang-format off
#include <boost/utility/enable_if.hpp>
#include <boost/numeric/odeint/algebra/algebra_dispatcher.hpp>
#include <boost/numeric/odeint/external/eigen/eigen.hpp>
#include <boost/numeric/odeint/stepper/symplectic_rkn_sb3a_mclachlan.hpp>
#include <boost/numeric/odeint/stepper/symplectic_rkn_sb3a_m4_mclachlan.hpp>
// clang-format on
#include <utility>

#include "solver.hpp"

namespace ex {
namespace {

namespace odeint = boost::numeric::odeint;

template <class Stepper>
class OdeintPeer : public Solver {
 public:
  explicit OdeintPeer(std::string name) : name_(std::move(name)) {}
  std::string name() const override { return name_; }
  Family family() const override { return Family::peer; }
  bool is_explicit() const override { return true; }
  int order() const override { return 4; }

  RunResult run(const Problem& pr, double h, long steps, const Observer* obs) const override {
    RunResult r{pr.q0, pr.p0, {}};
    long evals = 0;
    auto momentum = [&pr, &evals](const Vec& q, Vec& dpdt) {
      pr.force(q, dpdt);
      ++evals;
    };
    Stepper stepper;
    for (long n = 0; n < steps; ++n) {
      stepper.do_step(momentum, std::make_pair(std::ref(r.q), std::ref(r.p)), double(n) * h, h);
      if (obs) (*obs)(double(n + 1) * h, r.q, r.p);
    }
    r.stats.grad_evals = evals;
    r.stats.steps = steps;
    return r;
  }

 private:
  std::string name_;
};

}  // namespace

std::unique_ptr<Solver> make_mclachlan_sb3a() {
  using S = odeint::symplectic_rkn_sb3a_mclachlan<Vec, Vec, double, Vec, Vec, double,
                                                  odeint::vector_space_algebra>;
  return std::make_unique<OdeintPeer<S>>("Odeint sb3a (McLachlan)");
}

std::unique_ptr<Solver> make_mclachlan_sb3a_m4() {
  using S = odeint::symplectic_rkn_sb3a_m4_mclachlan<Vec, Vec, double, Vec, Vec, double,
                                                     odeint::vector_space_algebra>;
  return std::make_unique<OdeintPeer<S>>("Odeint sb3a-m4 (McLachlan)");
}

}  // namespace ex
