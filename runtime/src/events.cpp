#include "erkn/events.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "erkn/error.hpp"
#include "erkn/time_grid.hpp"
#include "format.hpp"

namespace erkn {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The probe's options: the run's solver settings, without the checks that belong to the run
// (its energy monitor, blow-up guard and stability check: the probe only takes shorter steps).
Options probe_options(const Options& run) {
  Options o = run;
  o.energy_tolerance = 0;
  o.blowup_guard = false;
  o.check_stability = false;
  return o;
}

std::vector<Event> validated(std::vector<Event> events) {
  for (std::size_t k = 0; k < events.size(); ++k) {
    if (!events[k].g) throw Error("event " + std::to_string(k) + " has no function g");
    if (events[k].direction < -1 || events[k].direction > 1)
      throw Error("event " + std::to_string(k) + ": direction must be -1, 0 or 1; got " +
                  std::to_string(events[k].direction));
  }
  return events;
}

// A zero in (t_n, t_{n+1}] in the event's direction: g rises from < 0 to >= 0, or falls from
// > 0 to <= 0 (a zero at t_{n+1} is counted there, not again at the next step).
bool crossed(const Event& e, double g_old, double g_new) {
  const bool rises = g_old < 0 && g_new >= 0, falls = g_old > 0 && g_new <= 0;
  return e.direction > 0 ? rises : e.direction < 0 ? falls : rises || falls;
}

}  // namespace

Events::Events(const Integrator& run, std::vector<Event> events)
    : events_(validated(std::move(events))),
      probe_(run.method(), run.system(), run.h(), run.q(), run.p(), probe_options(run.options()),
             run.t()) {
  remember(run);
  g_.resize(events_.size());
  for (std::size_t k = 0; k < events_.size(); ++k) g_[k] = events_[k].g(t_prev_, q_prev_, p_prev_);
}

void Events::remember(const Integrator& run) {
  t_prev_ = run.t();
  q_prev_ = run.q();
  p_prev_ = run.p();
}

bool Events::integrate(Integrator& run, double t_end, const Observer& observer, long every) {
  if (every < 1)
    throw Error("the observer interval must be >= 1 step; got " + std::to_string(every));
  const long whole = run.steps_until(t_end);  // (validates t_end)
  for (long n = 1; n <= whole; ++n) {
    if (step(run, false, t_end)) return observer(run.t(), run.q(), run.p()), true;
    if (n % every == 0) observer(run.t(), run.q(), run.p());
  }
  const bool shorter = TimeGrid(run.t(), run.h()).plan_to(t_end).shorter;
  if (shorter) {
    const bool stop = step(run, true, t_end);
    observer(run.t(), run.q(), run.p());
    if (stop) return true;
  } else if (whole % every != 0) {
    observer(run.t(), run.q(), run.p());
  }
  return false;
}

bool Events::integrate(Integrator& run, double t_end,
                       const Eigen::Ref<const Eigen::VectorXd>& times, const Observer& observer) {
  TimeGrid(run.t(), run.h()).require_output_times(t_end, times);
  const long whole = run.steps_until(t_end);
  Eigen::Index next = 0;
  std::vector<EventHit> pending;  // the output times before the end of the coming step
  for (long n = 1; n <= whole + 1; ++n) {
    const bool shorter = n > whole;
    const TimeGrid grid(run.t(), run.h());
    if (shorter && !grid.plan_to(t_end).shorter) break;
    pending.clear();
    for (; next < times.size() && (shorter ? t_end - times[next] > grid.tolerance(t_end)
                                           : run.steps_until(times[next]) == 0);
         ++next) {
      pending.push_back({0, times[next], {}, {}});
      run.state_at(pending.back().t, pending.back().q, pending.back().p);
    }
    const bool stop = step(run, shorter, t_end);
    for (const EventHit& out : pending)
      if (!stop || out.t <= run.t()) observer(out.t, out.q, out.p);
    if (stop) return true;
  }
  for (; next < times.size(); ++next) observer(times[next], run.q(), run.p());
  return false;
}

// One step of run (the shorter one to t_end if `shorter`), then the events.
bool Events::step(Integrator& run, bool shorter, double t_end) {
  if (shorter)
    run.integrate(t_end);
  else
    run.step(1);
  return after_step(run);
}

bool Events::after_step(Integrator& run) {
  if (probe_.h() != run.h()) probe_.set_step_size(run.h());  // (run's h changed in between)
  q_ = run.q(), p_ = run.p();
  const double t_new = run.t();
  const std::size_t first = hits_.size();
  const EventHit* stop = nullptr;
  for (std::size_t k = 0; k < events_.size(); ++k) {
    const double g_new = events_[k].g(t_new, q_, p_);
    if (crossed(events_[k], g_[k], g_new)) {
      EventHit hit{k, locate(k, t_new, g_new), q_, p_};
      if (hit.t != t_new) probe_.state_at(hit.t, hit.q, hit.p);
      hits_.push_back(std::move(hit));
    }
    g_[k] = g_new;
  }
  std::stable_sort(hits_.begin() + long(first), hits_.end(),
                   [](const EventHit& a, const EventHit& b) { return a.t < b.t; });
  for (std::size_t i = first; i < hits_.size() && !stop; ++i)
    if (events_[hits_[i].event].terminal) stop = &hits_[i];
  if (!stop) {  // (the new state is the next step's start)
    t_prev_ = t_new;
    q_prev_.swap(q_), p_prev_.swap(p_);
    return false;
  }
  hits_.resize(std::size_t(stop - hits_.data()) + 1);  // (none after the terminal one)
  run.set_state(hits_.back().q, hits_.back().p, hits_.back().t);
  remember(run);
  for (std::size_t k = 0; k < events_.size(); ++k) g_[k] = events_[k].g(t_prev_, q_prev_, p_prev_);
  return true;
}

// g_k at tau in [t_n, t_{n+1}]: the state by a step of the method of size tau - t_n from the
// state before the step (the probe starts there).
double Events::g_at(std::size_t k, double tau) {
  probe_.state_at(tau, q_tau_, p_tau_);
  return events_[k].g(tau, q_tau_, p_tau_);
}

// Illinois regula falsi on [t_n, t_new], g_k changing sign there; returns the end of the final
// bracket on g_new's side (g there has the new sign, so the zero is not found twice).
double Events::locate(std::size_t k, double t_new, double g_new) {
  probe_.set_state(q_prev_, p_prev_, t_prev_);
  double a = t_prev_, ga = g_[k], b = t_new, gb = g_new;
  if (gb == 0) return b;
  const double tol = 4 * kEps * std::max({std::abs(a), std::abs(b), probe_.h()});
  int side = 0;
  for (int it = 0; it < 200 && b - a > tol; ++it) {
    double c = b - gb * (b - a) / (gb - ga);
    if (!(c > a && c < b)) c = a + (b - a) / 2;
    const double gc = g_at(k, c);
    if (gc == 0 || (gc > 0) == (gb > 0)) {
      b = c, gb = gc;
      if (gb == 0) break;
      if (side == -1) ga /= 2;
      side = -1;
    } else {
      a = c, ga = gc;
      if (side == +1) gb /= 2;
      side = +1;
    }
  }
  return b;
}

}  // namespace erkn
