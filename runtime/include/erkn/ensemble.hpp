// erkn::Ensemble: many independent trajectories (different initial data or parameters) of one
// method and step size, integrated on the threads of one node.
//
// Each trajectory runs start to end on one thread with its own Integrator, so its result is
// bit-identical to a serial run whatever the number of threads and the order they pick
// trajectories in. A trajectory that fails (bad input, a stage that does not converge, a callback
// that throws) reports its error and the state of its last completed step; the others go on.
//
//   erkn::Ensemble ensemble(erkn::Method::by_name("SERKN2s4"), 0.05, 100,
//                           [](std::size_t i) {  // trajectory i: its system and initial data
//                             erkn::Member m;
//                             m.system.M = erkn::Stiffness::scalar(1.0 + 0.01 * double(i));
//                             m.system.gradient = [](const Eigen::VectorXd& q,
//                                                    Eigen::VectorXd& g) { g = q.array().sin(); };
//                             m.q0 = Eigen::VectorXd::Constant(1, 0.1 * double(i));
//                             m.p0 = Eigen::VectorXd::Zero(1);
//                             return m;
//                           });
//   std::vector<erkn::TrajectoryResult> r = ensemble.integrate(10.0);  // r[i]: trajectory i
//
// The member function and the System callbacks run concurrently on worker threads: they must
// not share mutable state between trajectories.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "erkn/integrator.hpp"
#include "erkn/method.hpp"
#include "erkn/system.hpp"

namespace erkn {

/// One trajectory: its system (the parameters) and its initial data at t = 0.
struct Member {
  System system;
  Eigen::VectorXd q0, p0;
};

/// The outcome of one trajectory.
struct TrajectoryResult {
  /// The state at t: t_end if ok(), else after the last completed step (the initial data if the
  /// integrator could not even be built; empty if building the member failed).
  Eigen::VectorXd q, p;
  double t = 0;
  Statistics statistics;
  /// Empty when the trajectory reached t_end; else the error that stopped it.
  std::string error;
  bool ok() const { return error.empty(); }
};

class Ensemble {
 public:
  /// Calls observer(i, integrator) after every step of trajectory i (in step order for one i,
  /// concurrently for different i).
  using Observer = std::function<void(std::size_t i, const Integrator& integrator)>;

  /// size trajectories; member(i) builds trajectory i when a thread starts it.
  Ensemble(const Method& method, double h, std::size_t size,
           std::function<Member(std::size_t)> member, const Options& options = {});
  /// The trajectories given as a list.
  Ensemble(const Method& method, double h, std::vector<Member> members,
           const Options& options = {});

  std::size_t size() const { return size_; }

  /// Integrates every trajectory from t = 0 to t_end on `threads` threads (0: one per hardware
  /// thread); result i belongs to trajectory i. Throws erkn::Error only for threads < 0.
  std::vector<TrajectoryResult> integrate(double t_end, int threads = 0,
                                          const Observer& observer = {}) const;
  /// The trajectories first..last-1 only (for distributing an ensemble over processes); result k
  /// belongs to trajectory first + k.
  std::vector<TrajectoryResult> integrate(double t_end, std::size_t first, std::size_t last,
                                          int threads = 0, const Observer& observer = {}) const;

 private:
  TrajectoryResult run(std::size_t i, double t_end, const Observer& observer) const;

  Method method_;
  double h_;
  std::size_t size_;
  std::function<Member(std::size_t)> member_;
  Options options_;
};

}  // namespace erkn
