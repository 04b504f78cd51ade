// Stormer-Verlet (velocity form) on the full force -Mq - grad U(q): one force evaluation a step.
#include "solver.hpp"

namespace ex {
namespace {

class StormerVerlet : public Solver {
 public:
  std::string name() const override { return "Störmer–Verlet"; }
  Family family() const override { return Family::peer; }
  bool is_explicit() const override { return true; }
  int order() const override { return 2; }
  bool suits_grid() const override { return true; }  // resolves M's frequencies, cheapest step

  RunResult run(const Problem& pr, double h, long steps, const Observer* obs) const override {
    RunResult r{pr.q0, pr.p0, {}};
    Vec f;
    pr.force(r.q, f);
    ++r.stats.grad_evals;
    for (long n = 0; n < steps; ++n) {
      r.p += 0.5 * h * f;
      r.q += h * r.p;
      pr.force(r.q, f);
      r.p += 0.5 * h * f;
      ++r.stats.grad_evals;
      ++r.stats.steps;
      if (obs) (*obs)(double(n + 1) * h, r.q, r.p);
    }
    return r;
  }
};

}  // namespace

std::unique_ptr<Solver> make_stormer_verlet() { return std::make_unique<StormerVerlet>(); }

}  // namespace ex
