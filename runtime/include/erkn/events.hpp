// erkn::Events: zeros of event functions g(t, q, p) along a run, as SciPy's solve_ivp finds them
// (direction, terminal), located to the method's own accuracy:
//
//   erkn::Integrator run(erkn::Method::by_name("ABA864"), sys, 0.05, q0, p0);
//   erkn::Events events(run, {{[](double, const auto& q, const auto&) { return q[0]; }, +1}});
//   events.integrate(run, 1000.0, [](double, const auto&, const auto&) {}, 1000);
//   for (const erkn::EventHit& e : events.hits()) use(e.t, e.q, e.p);  // a Poincare section
//
// After every step from (t_n, q_n, p_n) to t_{n+1}, each g is evaluated at the new state; a sign
// change (g(t_n) < 0 <= g(t_{n+1}) rising, g(t_n) > 0 >= g(t_{n+1}) falling) is a zero in
// (t_n, t_{n+1}]. It is located on tau -> g(tau, state(tau)), where state(tau) is one step of the
// method itself of size tau - t_n from (q_n, p_n) (what Integrator::state_at computes): the same
// symplectic method, so the located time is as accurate as the trajectory, O(h^order), and no
// interpolant of lower order enters. The root finder is the Illinois variant of regula falsi,
// stopped when the bracket is within 4 eps max(|t|, h); the reported time is the bracket's end
// on the new sign's side. Two zeros of one g within a step cancel and are not seen (choose h
// below the events' spacing); a zero exactly at the start of a run is not an event.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

#include "erkn/integrator.hpp"

namespace erkn {

struct Event {
  /// The event function: its zeros along the trajectory are the events.
  std::function<double(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& p)> g;
  /// +1: only zeros where g rises (negative to non-negative); -1: only where it falls; 0: both.
  int direction = 0;
  /// The run stops at this event's first zero (the integrator's state is then the event's).
  bool terminal = false;
};

struct EventHit {
  std::size_t event = 0;  ///< index of the event in the list given to Events
  double t = 0;           ///< the located time
  Eigen::VectorXd q, p;   ///< the state there
};

class Events {
 public:
  using Observer =
      std::function<void(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& p)>;

  /// Validates the events (g set, direction -1, 0 or 1; erkn::Error naming the first bad one)
  /// and records each g at run's current state. `run` is not kept: pass it to integrate.
  Events(const Integrator& run, std::vector<Event> events);

  /// Steps run to t_end as run.integrate(t_end, observer, every) does (the same steps, the same
  /// observer calls) and locates the events after every step. A terminal event ends the call
  /// early: run is set to the event's state and time (set_state: the grid restarts there) and
  /// observer is called there. Returns true when a terminal event stopped the run.
  bool integrate(Integrator& run, double t_end, const Observer& observer, long every = 1);
  /// As run.integrate(t_end, times, observer), with the events; after a terminal event, only the
  /// times up to it have been observed.
  bool integrate(Integrator& run, double t_end, const Eigen::Ref<const Eigen::VectorXd>& times,
                 const Observer& observer);

  /// The events found so far, in time order.
  const std::vector<EventHit>& hits() const { return hits_; }
  /// The work spent locating them (gradient evaluations of the shorter steps).
  const Statistics& statistics() const { return probe_.statistics(); }

 private:
  std::vector<Event> events_;
  std::vector<double> g_;  // each g at the current state of the run
  Integrator probe_;       // takes the shorter steps from the state before the step
  std::vector<EventHit> hits_;
  double t_prev_ = 0;
  Eigen::VectorXd q_prev_, p_prev_, q_, p_;  // the state before and after the step
  Eigen::VectorXd q_tau_, p_tau_;            // a state within the step (root finding)

  void remember(const Integrator& run);
  bool step(Integrator& run, bool shorter, double t_end);
  bool after_step(Integrator& run);
  double g_at(std::size_t k, double tau);
  double locate(std::size_t k, double t_new, double g_new);
};

}  // namespace erkn
