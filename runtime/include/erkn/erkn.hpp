// erkn: diagonal implicit symplectic extended RKN (ERKN) integrators for q'' + M q = -grad U(q).
//
// One header for everything: methods (erkn/method.hpp), the matrix M in its cheapest exact form
// (erkn/stiffness.hpp), the system (erkn/system.hpp), the integrator (erkn/integrator.hpp), events
// along a run (erkn/events.hpp), many trajectories on threads (erkn/ensemble.hpp) and the one
// exception type erkn::Error (erkn/error.hpp). A complete program (sine-Gordon, problem 1 of the
// paper; link with erkn::runtime):
//
//   #include <cmath>
//   #include <cstdio>
//   #include <erkn/erkn.hpp>
//   #include <numbers>
//
//   int main() {
//     const int N = 32;
//     const double dx = 2.0 / N, pi = std::numbers::pi;
//     Eigen::VectorXd col = Eigen::VectorXd::Zero(N), q0 = Eigen::VectorXd::Constant(N, pi), p0(N);
//     col[0] = 2 / (dx * dx), col[1] = col[N - 1] = -1 / (dx * dx);  // circulant(2,-1,..,-1)/dx^2
//     for (int i = 0; i < N; ++i) p0[i] = std::sqrt(N) * (0.01 + std::sin(2 * pi * (i + 1) / N));
//     erkn::System sys;
//     sys.M = erkn::Stiffness::circulant(col);
//     sys.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().sin(); };
//     sys.potential = [](const Eigen::VectorXd& q) { return -q.array().cos().sum(); };
//     erkn::Integrator run(erkn::Method::by_name("SERKN3s4(1)"), sys, 1.0 / 40, q0, p0);
//     const double H0 = run.energy();
//     run.integrate(10.0);
//     std::printf("u1(10) = %.10f  |H - H0| = %.1e  grad U evaluations: %ld\n", run.q()[0],
//                 std::abs(run.energy() - H0), run.statistics().gradient_evaluations);
//     return std::abs(run.energy() - H0) < 1e-2 ? 0 : 1;
//   }
//
// Methods: Method::all() lists every generated method; Method::by_name accepts the paper's name
// ("SERKN3s4(1)") or the id ("SERKN3s4_1"), Method::get(MethodId::SERKN3s4_1) the id.
#pragma once

#include "erkn/accuracy.hpp"
#include "erkn/advisor.hpp"
#include "erkn/ensemble.hpp"
#include "erkn/error.hpp"
#include "erkn/events.hpp"
#include "erkn/integrator.hpp"
#include "erkn/method.hpp"
#include "erkn/stiffness.hpp"
#include "erkn/system.hpp"
