#include "erkn/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "accuracy_pilot.hpp"
#include "clock.hpp"
#include "erkn/advisor.hpp"
#include "erkn/error.hpp"
#include "format.hpp"

namespace erkn {
namespace {

using detail::Pilot;

// Force evaluations per step: s, one less when the last kick is the next step's first (FSAL);
// a modified kick's G (a Hessian-vector product) counts as one more gradient, what a closed
// form costs (1.3 gradients on sine-Gordon and Duffing, issue 18), unknown for a user's.
int gradients_per_step(const Method& m) {
  const auto& t = m.table();
  const bool fsal = m.is_explicit() && m.stages() > 1 && t.c[0] == 0 && t.c[m.stages() - 1] == 1;
  int products = 0;
  for (double e : m.modified()) products += e != 0;
  if (fsal && !m.modified().empty() && m.modified()[0] != 0) --products;
  return m.stages() - (fsal ? 1 : 0) + products;
}

// r = min(1, max |eigenvalue of U's Hessian at q0| / smallest eigenvalue of M): the size of the
// perturbation against the linear part (1 where M has a zero eigenvalue or no bounds).
double perturbation(const System& s, const HessianBounds& b) {
  const double smallest = s.M.eigenvalues().minCoeff();
  const double hessian = std::max(std::abs(b.lo), std::abs(b.hi));
  return smallest > 0 && (b.lo != 0 || b.hi != 0) ? std::min(1.0, hessian / smallest) : 1.0;
}

// The Hessian bounds at q0 when affordable (a user Hessian, or d <= 256 finite differences).
HessianBounds bounds_at(const System& s, const Eigen::VectorXd& q0) {
  return s.hessian || q0.size() <= 256 ? hessian_bounds_at(s, q0) : HessianBounds{};
}

void validate(const AccuracyRequest& r, double t0, double t_end) {
  if (!(std::isfinite(t0) && std::isfinite(t_end) && t_end > t0))
    throw Error("solve: t_end must be finite and after t0, got t0 = " + format(t0) +
                ", t_end = " + format(t_end));
  if (!(std::isfinite(r.tol) && r.tol >= 0))
    throw Error("solve: tol must be finite and >= 0, got " + format(r.tol));
  if (!(std::isfinite(r.h) && r.h >= 0))
    throw Error("solve: h must be finite and >= 0 (0: chosen), got " + format(r.h));
  if (!(r.pilot_fraction > 0 && r.pilot_fraction <= 1))
    throw Error("solve: pilot_fraction must lie in (0, 1], got " + format(r.pilot_fraction));
  if (!(r.safety > 0 && r.safety <= 1))
    throw Error("solve: safety must lie in (0, 1], got " + format(r.safety));
  if ((r.method == "auto" || r.h == 0) && r.tol == 0)
    throw Error("solve: give tol (the requested error) to choose " +
                std::string(r.method == "auto" ? "the method" : "the step size h") +
                ", or both a method and h");
}

// The explicit methods; those with modified kicks only if the system forms G.
std::vector<const Method*> candidates(const AccuracyRequest& r, const System& system) {
  if (r.method != "auto") return {&Method::by_name(r.method)};
  const bool modified_force = system.hessian_vector_product || system.hessian;
  std::vector<const Method*> out;
  for (const Method& m : Method::all())
    if (m.is_explicit() && (modified_force || !m.has_modified_kicks())) out.push_back(&m);
  return out;
}

// Everything the search knows: the request, the pilots run so far and their cost.
struct Search {
  detail::PilotRequest pilot;
  double target = 0, r = 1;
  std::vector<const Method*> methods;
  std::vector<std::pair<const Method*, Pilot>> piloted;
  double cpu = 0;
  long gradients = 0;
  HessianBounds bounds;         // at q0 (zero when not affordable)
  double F = 1;                 // the problem factor of the model, from the first pilot
  double cpu_per_gradient = 0;  // of the first pilot
  std::map<const Method*, detail::ErrorShape> shapes;  // each candidate's, at r (made once)
  std::map<const Method*, Candidate> modelled;  // each candidate's model prediction (fixed by F)
  double relief = 1;  // the growth probe's measured growth over the pilot's linear one
};

const detail::ErrorShape& shape_of(const Search& s, const Method& m) { return s.shapes.at(&m); }

const Pilot* pilot_of(const Search& s, const Method* m) {
  for (const auto& [pm, pl] : s.piloted)
    if (pm == m) return &pl;
  return nullptr;
}

// The pilot request with m's error shape.
detail::PilotRequest shaped(const Search& s, const Method& m) {
  detail::PilotRequest r = s.pilot;
  r.shape = shape_of(s, m);
  return r;
}

// m's step and CPU from the model calibrated by the first pilot (F, cost per gradient).
Candidate modelled(const Method& m, const Search& s) {
  Candidate c{std::string(m.name()), false, 0, s.target, 0};
  const double span = s.pilot.span;
  c.h = shape_of(s, m).step_at(s.target / (span * s.F), span);
  c.predicted_cpu = s.cpu_per_gradient * gradients_per_step(m) * std::ceil(span / c.h);
  return c;
}

// The predicted step, error and CPU of m: from its own pilot, else from the calibrated model.
Candidate predict(const Method& m, const Search& s) {
  Candidate c{std::string(m.name()), false, 0, s.target, 0};
  const double span = s.pilot.span;
  if (const Pilot* pl = pilot_of(s, &m)) {
    c.piloted = true;
    const detail::PilotRequest r = shaped(s, m);
    c.h = detail::step_for(r, *pl, s.target);
    c.estimated_error = pl->error * r.shape(c.h) / r.shape(pl->h);
    c.predicted_cpu = pl->cpu_per_gradient * gradients_per_step(m) * std::ceil(span / c.h);
    return c;
  }
  return s.modelled.at(&m);
}

// Pilots m from h_start; records it (and its cost) when it succeeds. Returns success.
bool run_pilot(Search& s, const Method& m, double h_start, std::string& failures) {
  Pilot pl = detail::calibrated_pilot(m, shaped(s, m), h_start, s.target);
  s.cpu += pl.cpu, s.gradients += pl.gradients;
  if (!pl.ok) {
    failures +=
        std::string(failures.empty() ? "" : "; ") + std::string(m.name()) + ": " + pl.failure;
    return false;
  }
  if (s.piloted.empty()) {
    const double base = shape_of(s, m)(pl.h) * s.pilot.span;
    s.F = base > 0 && pl.error > 0 ? pl.error / base : 1;
    s.cpu_per_gradient = pl.cpu_per_gradient;
    for (const Method* other : s.methods) s.modelled.emplace(other, modelled(*other, s));
  }
  s.piloted.emplace_back(&m, pl);
  return true;
}

std::vector<Candidate> ranked(const Search& s) {
  std::vector<Candidate> out;
  for (const Method* m : s.methods) out.push_back(predict(*m, s));
  std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) {
    return a.predicted_cpu < b.predicted_cpu;
  });
  return out;
}

// The first pilot: the model's best method at F = 1 (the next ones if its pilot fails), from the
// coarsest step (two over the pilot interval): refining costs less than coarsening.
void first_pilot(Search& s) {
  std::vector<std::pair<double, const Method*>> order;
  const double span = s.pilot.span;
  for (const Method* m : s.methods)
    order.emplace_back(gradients_per_step(*m) / shape_of(s, *m).step_at(s.target / span, span), m);
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string failures;
  for (size_t i = 0; i < order.size() && i < 3; ++i)
    if (run_pilot(s, *order[i].second, s.pilot.pilot / 2, failures)) return;
  throw Error("solve: no method could be piloted on this problem (" + failures + ")");
}

// Pilots what the calibrated model predicts cheaper than every piloted method (by 20 %; at
// most two more pilots); a method whose pilot fails leaves the candidates.
void more_pilots(Search& s) {
  std::string failures;
  for (int k = 0; k < 2; ++k) {
    const std::vector<Candidate> list = ranked(s);
    const auto best =
        std::find_if(list.begin(), list.end(), [](const Candidate& c) { return c.piloted; });
    if (list.front().piloted || list.front().predicted_cpu >= 0.8 * best->predicted_cpu) return;
    const Method& m = Method::by_name(list.front().method);
    if (!run_pilot(s, m, std::min(s.pilot.pilot / 2, 2 * list.front().h), failures))
      s.methods.erase(std::find(s.methods.begin(), s.methods.end(), &m));
  }
}

// The candidate with the fewest gradients per step (the growth probe: any method shows the
// growth law, the cheapest per step shows it for the least).
const Method* cheapest_per_step(const Search& s) {
  const Method* out = nullptr;
  for (const Method* m : s.methods)
    if (!out || gradients_per_step(*m) < gradients_per_step(*out)) out = m;
  return out;
}

// The chosen candidate with its estimate's linear growth replaced by the probe's measured growth
// (detail::growth_relief) and its step for the target; unchanged when the probe would cost more
// than a tenth of the run (3 probe steps per step over 1/8 of the span at 2 h) or the pilot sat at
// round-off. The probe's step is 2 h: clear of round-off, still asymptotic on the scenes.
Candidate with_measured_growth(Search& s, Candidate c) {
  const Method& m = Method::by_name(c.method);
  const Method* probe = cheapest_per_step(s);
  const Pilot* pl = pilot_of(s, &m);
  const double span = s.pilot.span, h_probe = 2 * c.h;
  if (!pl || pl->at_roundoff || c.estimated_error <= 0) return c;
  const double probe_cost =
      3.0 * gradients_per_step(*probe) * double(detail::probe_steps(s.pilot, h_probe));
  if (probe_cost > 0.1 * gradients_per_step(m) * span / c.h) return c;
  const detail::Growth g = detail::growth_relief(*probe, s.pilot, h_probe, pl->interval);
  s.gradients += g.gradients;
  s.relief = g.relief;
  const detail::ErrorShape& shape = shape_of(s, m);
  const double h = shape.step_at(shape(c.h) * s.target / (g.relief * c.estimated_error), span);
  c.estimated_error *= g.relief * shape(h) / shape(c.h);
  c.h = h;
  return c;
}

// A user-given h: the cheapest candidate predicted to reach the target with it, else the most
// accurate one.
Candidate with_given_step(const Search& s, double h) {
  std::vector<Candidate> list = ranked(s);
  for (Candidate& c : list) {
    const Method& m = Method::by_name(c.method);
    const Pilot* pl = pilot_of(s, &m);
    c.h = h;
    c.estimated_error =
        pl ? pl->error * std::pow(h / pl->h, m.order()) : s.F * s.pilot.span * shape_of(s, m)(h);
    c.predicted_cpu = s.cpu_per_gradient * gradients_per_step(m) * std::ceil(s.pilot.span / h);
  }
  const auto reaches = [&](const Candidate& c) { return c.estimated_error <= s.target; };
  const auto cheaper = [&](const Candidate& a, const Candidate& b) {
    return reaches(a) != reaches(b) ? reaches(a)
           : reaches(a)             ? a.predicted_cpu < b.predicted_cpu
                                    : a.estimated_error < b.estimated_error;
  };
  return *std::min_element(list.begin(), list.end(), cheaper);
}

// The advisor's word on h (M's spectrum, Hessian bounds at q0 when affordable): a flagged h is
// replaced by the suggestion when that is smaller. The suggestion is searched in 1 % steps of h
// (the advisor's default 0.1 %): a step up to 1 % shorter costs up to 1 % more run; the search
// checks every mode at each step it tries (FPU at 1e-4: 0.49 ms of a 0.05 ms run with 0.1 %).
double advised(const Method& m, const System& sys, const HessianBounds& bounds, double h,
               std::string& note) {
  AdvisorOptions o;
  o.search_step = 1e-2;
  const StepSizeAdvice a = advise_step_size(m, detail::distinct(sys.M.eigenvalues()), h, bounds, o);
  if (a.safe()) {
    note = "the advisor finds no pole, instability or resonance at this h";
    return h;
  }
  const std::string hazard(to_string(a.findings.front().hazard));
  if (std::isfinite(a.suggested_h) && a.suggested_h < h) {
    note = "the advisor flags " + hazard + " at h = " + format(h, 4) + "; its suggestion taken";
    return a.suggested_h;
  }
  note = "the advisor flags " + hazard + " at h = " + format(h, 4) + " (no smaller h suggested)";
  return h;
}

}  // namespace
}  // namespace erkn

namespace erkn {
namespace {

std::string reason_of(const Choice& c, const Search& s, const std::string& advice) {
  const Method& m = Method::by_name(c.method);
  const Pilot* pl = pilot_of(s, &m);
  std::string out = c.method + " (" + std::string(m.kind_name()) + ", order " +
                    std::to_string(m.order()) + ", error constant " +
                    format(m.error_constant(), 3) + "; perturbation size r = " + format(s.r, 3) +
                    ")";
  if (pl)
    out += ": its pilot over " + format(s.pilot.pilot, 4) + " of " + format(s.pilot.span, 4) +
           " at h = " + format(pl->h, 4) + " and h/2 estimates " + format(pl->error, 3) +
           " at t_end (step doubling, error grown linearly in t)";
  if (s.relief < 1)
    out += "; a probe over 1/8 of the span measures " + format(s.relief, 3) + " of that growth";
  out += "; h = " + format(c.h, 6) + " aims at " + format(s.target, 3) + " (estimated " +
         format(c.estimated_error, 3) + ")";
  if (c.candidates.size() > 1)
    out += "; next cheapest: " + c.candidates[1].method + " (predicted CPU " +
           format(c.candidates[1].predicted_cpu / c.candidates.front().predicted_cpu, 3) + "x)";
  return out + "; " + advice + ".";
}

}  // namespace

Choice choose_method_and_step(const System& system, const Eigen::VectorXd& q0,
                              const Eigen::VectorXd& p0, double t0, double t_end,
                              const AccuracyRequest& request, const Options& options) {
  validate(request, t0, t_end);
  if (request.tol == 0) throw Error("solve: choosing a method or h needs tol > 0");
  const double cpu_0 = detail::cpu_seconds();
  Search s;
  s.pilot = {&system, &q0, &p0, options, t_end - t0, (t_end - t0) * request.pilot_fraction, {}};
  s.target = request.safety * request.tol;
  s.methods = candidates(request, system);
  if (!system.gradient) throw Error("solve: the system has no gradient");
  s.bounds = bounds_at(system, q0);
  s.r = perturbation(system, s.bounds);
  for (const Method* m : s.methods) s.shapes.emplace(m, detail::error_shape(*m, s.r));
  first_pilot(s);
  if (request.h == 0) more_pilots(s);
  const std::vector<Candidate> list = ranked(s);
  Candidate best = request.h > 0 ? with_given_step(s, request.h)
                                 : *std::find_if(list.begin(), list.end(),
                                                 [](const Candidate& c) { return c.piloted; });
  Choice c{best.method, best.h, best.estimated_error, 0, 0, list, ""};
  std::string advice = "h given by the user";
  const Method& m = Method::by_name(c.method);
  if (request.h == 0) {
    const Candidate grown = with_measured_growth(s, best);
    for (Candidate& listed : c.candidates) {
      if (listed.method != grown.method) continue;
      listed.predicted_cpu *= best.h / grown.h;
      listed.h = grown.h, listed.estimated_error = grown.estimated_error;
    }
    best = grown, c.estimated_error = grown.estimated_error;
    const double h = advised(m, system, s.bounds, best.h, advice);
    c.h = s.pilot.span / std::ceil(s.pilot.span / h * (1 - 1e-12));  // whole steps to t_end
    const detail::ErrorShape& shape = shape_of(s, m);
    c.estimated_error *= shape(c.h) / shape(best.h);
  }
  c.reason = reason_of(c, s, advice);
  c.pilot_gradient_evaluations = s.gradients;
  c.pilot_cpu = detail::cpu_seconds() - cpu_0;
  return c;
}

Solution solve(const System& system, const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
               double t0, double t_end, const AccuracyRequest& request, const Options& options) {
  validate(request, t0, t_end);
  Solution out;
  if (request.method == "auto" || request.h == 0)
    out.choice = choose_method_and_step(system, q0, p0, t0, t_end, request, options);
  out.method = out.choice ? out.choice->method : request.method;
  out.h = out.choice ? out.choice->h : request.h;
  Integrator run(Method::by_name(out.method), system, out.h, q0, p0, options);
  run.step(run.steps_until(t_end - t0));
  run.integrate(t_end - t0);  // a shorter last step when t_end is off the grid
  out.q = run.q(), out.p = run.p(), out.t = t0 + run.t();
  out.statistics = run.statistics();
  return out;
}

}  // namespace erkn
