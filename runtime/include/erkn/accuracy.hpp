// Accuracy-driven runs: from a requested global error to a method and a step size.
//
//   erkn::AccuracyRequest want;
//   want.tol = 1e-8;                       // max-norm error of q at t_end (absolute)
//   erkn::Solution sol = erkn::solve(system, q0, p0, 0.0, 100.0, want);
//   // sol.q, sol.p at t = 100; sol.choice->method, ->h, ->estimated_error, ->reason
//
// How the choice is made (choose_method_and_step):
//  1. Candidates: every explicit method of the registry (one gradient per stage, no stage
//     solves) or the one the user names. A priori model of the global error at t_end,
//         E_m(h) = F (t_end - t0) sum_K r^K C_K h^(g_K),
//     g_K, C_K the certified generalized orders and the generator's error constants
//     (Method::generalized_error_constant) of the eps^K terms, r = min(1, max |eigenvalue of
//     U's Hessian at q0| / smallest eigenvalue of M) the size of the perturbation (1 when M has
//     a zero eigenvalue or d > 256 without a user Hessian), F an unknown problem factor.
//  2. Pilot on the user's problem: the model's best method steps a pilot interval (a fraction
//     of the run) with h and h/2; the step-doubling difference, times 2^p/(2^p - 1) with p the
//     model's slope at h, estimates the error of the h run at the checkpoints t_i of the
//     pilot's second half; grown linearly to t_end (max of e(t_i) (t_end - t0)/(t_i - t0)) it
//     gives E(h) and F. h is refined until the estimate lies within 1000x of the target.
//  3. With F, the model predicts every candidate's step and CPU (cost per gradient measured in
//     the pilot); a cheaper-looking method is piloted too; the one with the least predicted CPU
//     at E = safety * tol wins, its h from E_m(h) / E_m(h_pilot) = target / E(h_pilot).
//  4. Growth probe: the pilot's linear growth bounds errors that never cancel; on many orbits
//     they do (the error after the pilot stays bounded: sine-Gordon, FPU, Duffing). The
//     cheapest method per step is stepped with 2h and h over 1/8 of the span; its step-doubling
//     envelope's growth from the pilot interval on (extrapolated as t^beta, beta in [0, 1] from
//     its last two octaves) replaces the linear growth when smaller, and h is solved again.
//     Skipped when it would cost more than a tenth of the run.
//  5. The advisor (erkn/advisor.hpp) checks h on M's spectrum and the Hessian bounds at q0;
//     a flagged h is replaced by its suggestion when that is smaller.
// A user-given method or h is kept. The estimate assumes the error grows at most linearly after
// the probe (symplectic methods on regular motion): on chaotic orbits it can be low.
// The pilot costs a few hundred steps: on runs of microseconds it dominates the CPU.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "erkn/integrator.hpp"
#include "erkn/system.hpp"

namespace erkn {

struct AccuracyRequest {
  double tol = 0;                    ///< requested max-norm error of q at t_end; 0: none
  std::string method = "auto";       ///< "auto": chosen; else kept (name or id)
  double h = 0;                      ///< 0: chosen; > 0: kept
  double pilot_fraction = 1.0 / 32;  ///< pilot interval / (t_end - t0), in (0, 1]
  double safety = 1;                 ///< the step aims at safety * tol, in (0, 1]
};

/// One method the choice considered.
struct Candidate {
  std::string method;
  bool piloted = false;        ///< run on the user's problem (else predicted from the model)
  double h = 0;                ///< the step it would take
  double estimated_error = 0;  ///< at t_end with that h
  double predicted_cpu = 0;    ///< seconds of the run
};

struct Choice {
  std::string method;
  double h = 0;
  double estimated_error = 0;  ///< of q at t_end (max norm)
  double pilot_cpu = 0;        ///< CPU seconds spent choosing (pilots, Hessian bounds, advisor)
  long pilot_gradient_evaluations = 0;
  std::vector<Candidate> candidates;  ///< by predicted CPU
  std::string reason;                 ///< a human-readable account of the choice
};

/// The method and step for `request` (tol > 0, or a given method and h). erkn::Error for invalid
/// input (tol or h negative or not finite, t_end <= t0, unknown method, fractions out of range)
/// or when no candidate can be piloted (every pilot failed: the message says why).
Choice choose_method_and_step(const System& system, const Eigen::VectorXd& q0,
                              const Eigen::VectorXd& p0, double t0, double t_end,
                              const AccuracyRequest& request, const Options& options = {});

struct Solution {
  Eigen::VectorXd q, p;  ///< at t
  double t = 0;
  std::string method;
  double h = 0;
  Statistics statistics;         ///< of the run (the choice's cost is in choice->pilot_cpu)
  std::optional<Choice> choice;  ///< set when the method or h was chosen
};

/// Integrates from (q0, p0) at t0 to t_end with the request's method and h, choosing what is
/// "auto" / 0 by choose_method_and_step (tol > 0 needed then).
Solution solve(const System& system, const Eigen::VectorXd& q0, const Eigen::VectorXd& p0,
               double t0, double t_end, const AccuracyRequest& request,
               const Options& options = {});

}  // namespace erkn
