// The narrow interface every integrator of the experiments is driven through: integrate a problem
// with a fixed step and report q, p and honest counts. Timing is done by the caller, around run().
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "problem.hpp"

namespace ex {

enum class Family { erkn, rkn, peer };

struct RunStats {
  long grad_evals = 0;        ///< evaluations of grad U (for peers: of the full force -Mq - grad U)
  long stage_iterations = 0;  ///< fixed-point / Newton iterations over all stage solves
  long stage_solves = 0;      ///< implicit stage systems solved (0 for explicit methods)
  long steps = 0;
};

struct RunResult {
  Vec q, p;
  RunStats stats;
};

/// Called after every step with t_{n+1}, q_{n+1}, p_{n+1}.
using Observer = std::function<void(double t, const Vec& q, const Vec& p)>;

class Solver {
 public:
  virtual ~Solver() = default;
  virtual std::string name() const = 0;  ///< the paper's name, or the peer's
  virtual Family family() const = 0;
  virtual int order() const = 0;
  /// True when q'' + Mq = 0 is integrated exactly (no step-size limit from M's frequencies).
  virtual bool exact_for_linear_part() const { return false; }
  /// True when no stage needs solving: every force evaluation is at a known point.
  virtual bool is_explicit() const = 0;
  /// Linear stability on y'' = -eps y (the V = 0 line of the (V, z) charts): the smallest z = h^2
  /// eps > 0 at which |tr S(0, z)| > 2 (or S is singular), found on a geometric grid z = 0.01 ..
  /// 1e4 and refined by bisection; empty when none there or the solver cannot tell.
  virtual std::optional<double> first_unstable_z() const { return std::nullopt; }
  /// True for the methods of the source paper (read from the registry; false for peers).
  virtual bool from_paper() const { return false; }
  /// For an RKN limit: the name of the first registry ERKN method whose V -> 0 limit it is (the
  /// same nodes and coefficients at V = 0); empty otherwise.
  virtual std::string limit_of() const { return ""; }
  /// Run in the large-grid scenes: a step is cheap at large d (no dense solves) and M's
  /// frequencies are integrated exactly or resolved (Verlet); the rest is in the P1-P3 charts.
  virtual bool suits_grid() const { return false; }
  /// Integrates from t = 0 with `steps` steps of size h (coefficient setup included); throws on
  /// failure (a pole of the method, a stage solver that does not converge).
  virtual RunResult run(const Problem& problem, double h, long steps,
                        const Observer* observer) const = 0;
};

using SolverList = std::vector<std::unique_ptr<Solver>>;

/// The search behind Solver::first_unstable_z for a predicate "S(0, z) is unstable".
std::optional<double> first_unstable_z(const std::function<bool(double z)>& unstable);

std::unique_ptr<Solver> make_stormer_verlet();
std::unique_ptr<Solver> make_mclachlan_sb3a();     ///< Boost.Odeint symplectic_rkn_sb3a_mclachlan
std::unique_ptr<Solver> make_mclachlan_sb3a_m4();  ///< Boost.Odeint ..._sb3a_m4_mclachlan
std::unique_ptr<Solver> make_gauss2();             ///< 2-stage Gauss-Legendre, Nystrom form
/// The exact-flow splitting peers (splitting.hpp): Strang, SRKN6b, SRKN14a, ABA(10,6,4),
/// mollified impulse, the force-gradient OMF4 (4MN3F3GP) and the processed PMLF6.
SolverList make_splitting_peers();
/// Every ERKN method and RKN limit of the runtime's registry, in its order, each method once:
/// a method identical to an earlier one (identical_registry_methods) is left out.
SolverList make_erkn_solvers();
/// A registry method left out of make_erkn_solvers and the earlier one it is identical to (same
/// kind, stages and coefficients).
struct Twin {
  std::string name, same_as;
};
std::vector<Twin> identical_registry_methods();
/// The ERKN/RKN methods followed by the peers.
SolverList all_solvers();

}  // namespace ex
