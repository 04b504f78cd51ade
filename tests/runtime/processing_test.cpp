// Processed methods psi = pi o K o pi^-1 (Method::is_processed): the stepper steps the kernel K,
// applies pi^-1 when a state is set and pi to every state a user sees. Checked against a
// processor written here independently around the kernel stepped alone; the kernel alone has
// its own, lower order (the registry's order test checks psi's); the statistics count the
// processor; every accepted state can be read (pi's image of a finite kernel state can overflow:
// such a step is refused). (The MPI grid integrator refuses these methods: tests/mpi.)
#include <gtest/gtest.h>

#include <cstdio>
#include <deque>
#include <optional>
#include <string>

#include "problems.hpp"
#include "refusals.hpp"

namespace erkn::test {
namespace {

using Vec = Eigen::VectorXd;

std::vector<Method> processed_methods() {
  std::vector<Method> out;
  for (const Method& m : Method::all())
    if (m.is_processed()) out.push_back(m);
  return out;
}

// The kernel K alone: the table without its processor.
Method kernel_of(const Method& m) {
  static std::deque<generated::Table> tables;
  tables.push_back(m.table());
  tables.back().npre = 0;
  return Method(m.id(), &tables.back());
}

// pi^-1 (sign 1) or pi (sign -1) from the table, for a scalar M = w^2 I: drifts are rotations,
// kicks p -= sign h (y grad U + h^2 v 2 Hess U grad U). Written from erkn/table.hpp's contract,
// not from the stepper.
void processor(const Method& m, const problems::Problem& P, double w, double h, double sign, Vec& q,
               Vec& p) {
  const generated::Table& t = m.table();
  const int n = t.npre;
  auto drift = [&](int k) {
    const double tau = sign * h * t.pre_drift[k];
    const Vec q0 = q;
    q = std::cos(w * tau) * q0 + std::sin(w * tau) / w * p;
    p = -w * std::sin(w * tau) * q0 + std::cos(w * tau) * p;
  };
  auto kick = [&](int k) {
    Vec g(q.size()), hv(q.size());
    P.grad_u(q, g);
    P.hessian_vector_u(q, g, hv);
    p -= sign * h * (t.pre_kick[k] * g + h * h * t.pre_modified[k] * 2 * hv);
  };
  for (int j = 0; j <= 2 * n; ++j) {
    const int k = sign > 0 ? j : 2 * n - j;
    if (k % 2 == 0)
      drift(k / 2);
    else
      kick(k / 2);
  }
}

// Every observed state is pi(K^k(pi^-1(y0))); negative control: the kernel's own states differ.
TEST(Processing, ObservedStatesArePiOfTheKernelsStates) {
  const problems::Problem P = problems::henon_heiles();
  const double w = 1, h = 0.2;
  for (const Method& m : processed_methods()) {
    SCOPED_TRACE(std::string(m.name()));
    Vec q = P.q0, p = P.p0;
    processor(m, P, w, h, 1, q, p);
    Integrator psi(m, problems::system(P), h, P.q0, P.p0),
        kernel(kernel_of(m), problems::system(P), h, q, p);
    EXPECT_LT((psi.q() - P.q0).norm() + (psi.p() - P.p0).norm(), 1e-14);  // pi o pi^-1 = id
    double worst = 0, kernel_offset = 0;
    psi.integrate(3.0, [&](double, const Vec& qs, const Vec& ps) {
      kernel.step();
      Vec qk = kernel.q(), pk = kernel.p();
      kernel_offset = std::max(kernel_offset, (qk - qs).norm());
      processor(m, P, w, h, -1, qk, pk);
      worst = std::max(worst, (qk - qs).norm() + (pk - ps).norm());
    });
    EXPECT_LT(worst, 1e-12);
    EXPECT_GT(kernel_offset, 1e-5);
  }
}

// The kernel alone has a lower order than psi (processing is what the order comes from); psi's
// own order is the registry's order test.
TEST(Processing, TheKernelAloneHasALowerOrder) {
  const problems::Problem P = problems::henon_heiles();
  const double T = 2;
  for (const Method& m : processed_methods()) {
    SCOPED_TRACE(std::string(m.name()));
    auto error = [&](const Method& method, long n) {
      Integrator fine(m, problems::system(P), T / double(8 * n), P.q0, P.p0);
      Integrator run(method, problems::system(P), T / double(n), P.q0, P.p0);
      fine.integrate(T), run.integrate(T);
      return (run.q() - fine.q()).norm();
    };
    const std::vector<long> n = {16, 23, 32, 45};
    std::vector<double> psi, kernel;
    for (long k : n) psi.push_back(error(m, k)), kernel.push_back(error(kernel_of(m), k));
    const double kernel_slope = fitted_slope(n, kernel), psi_slope = fitted_slope(n, psi);
    std::printf("%-10s order %d (kernel %d): observed %.2f, kernel alone %.2f\n",
                std::string(m.name()).c_str(), m.order(), m.kernel_order(), psi_slope,
                kernel_slope);
    EXPECT_LT(kernel_slope, m.order() - 0.5);
    EXPECT_NEAR(kernel_slope, m.kernel_order(), 0.3);
  }
}

// pi^-1 at construction and set_state, pi once per state a call of steps ends at (it is read
// there: EveryAcceptedStateCanBeRead), each with its kicks' gradients (and Hessian-vector
// products) in the counts; reading the state then costs nothing more.
TEST(Processing, StatisticsCountTheProcessor) {
  const problems::Problem P = problems::henon_heiles();
  for (const Method& m : processed_methods()) {
    SCOPED_TRACE(std::string(m.name()));
    const int kicks = m.table().npre;
    long modified = 0;
    for (int k = 0; k < kicks; ++k) modified += m.table().pre_modified[k] != 0;
    Integrator run(m, problems::system(P), 0.1, P.q0, P.p0);
    EXPECT_EQ(run.statistics().processor_applications, 1);
    EXPECT_EQ(run.statistics().gradient_evaluations, kicks);
    EXPECT_EQ(run.statistics().hessian_vector_products, modified);
    const Statistics start = run.statistics();
    run.step(5);
    const Statistics before = run.statistics();
    EXPECT_EQ(before.processor_applications, start.processor_applications + 1);
    EXPECT_EQ(before.gradient_evaluations - start.gradient_evaluations,  // (kernel: 1 per stage)
              before.stage_iterations - start.stage_iterations + kicks);
    run.q(), run.p(), run.q();  // (the state step(5) read)
    const Statistics& after = run.statistics();
    EXPECT_EQ(after.processor_applications, before.processor_applications);
    EXPECT_EQ(after.gradient_evaluations, before.gradient_evaluations);
    EXPECT_EQ(after.hessian_vector_products, before.hessian_vector_products);
    run.set_state(P.q0, P.p0, 0.0);
    EXPECT_EQ(run.statistics().processor_applications, before.processor_applications + 1);
    EXPECT_EQ(run.statistics().hessian_vector_products, before.hessian_vector_products + modified);
  }
  // Control: an unprocessed method applies none.
  Integrator plain(Method::by_name("Strang"), problems::system(P), 0.1, P.q0, P.p0);
  plain.step(5), plain.q();
  EXPECT_EQ(plain.statistics().processor_applications, 0);
}

// q'' + q = -q^3 (U = q^4 / 4, d = 1), whose processor's kicks overflow on a finite kernel
// state of large enough energy: a quartic force cubes q, its modified force is 6 q^5.
System quartic() {
  System s;
  s.M = Stiffness::scalar(1.0);
  s.gradient = [](const Vec& q, Vec& g) { g = q.array().cube().matrix(); };
  s.hessian_vector_product = [](const Vec& q, const Vec& v, Vec& hv) {
    hv = (3 * q.array().square() * v.array()).matrix();
  };
  return s;
}

// The run of one processed method from q0 = a with step h, `steps` steps one step() at a time:
// after each step() that succeeds q() and p() are read (and must be: finite), a refused one
// changes nothing. Returns the message of the refused step ("" if none) and leaves the run at
// the state before it.
std::string step_by_step(Integrator& run, long steps) {
  for (long n = 0; n < steps; ++n) {
    const Snapshot before(run);
    const std::string refused = error_of([&] { run.step(); });
    if (!refused.empty()) {
      before.expect_same(run);
      return refused;
    }
    std::string read = error_of([&] { EXPECT_TRUE(run.q().allFinite() && run.p().allFinite()); });
    EXPECT_EQ(read, "") << "the state after step " << run.statistics().steps << " cannot be read";
    if (!read.empty()) return read;
  }
  return "";
}

// Every accepted step's state can be read: the integrator refuses, naming it, the step whose
// kernel state pi maps to a non-finite one (on this quartic system, from q0 = 1 ... 3, h = 0.5
// ... 2, every processed method reaches one after at least one good step; on main before this
// test step() accepted such a step and q() threw). One step() at a time it is the step refused;
// integrate() over the same steps (one batch) keeps the same steps, bit for bit the same state,
// and names the same step; integrate() from there to half a step beyond (an off-grid step) is
// refused or succeeds, and a refusal changes nothing. Negative control: the runs of small h q0
// end without error, batch and step by step alike.
TEST(Processing, EveryAcceptedStateCanBeRead) {
  Options unguarded;  // (the guard would return to its last check instead)
  unguarded.blowup_guard = false;
  const long steps = 60;
  for (const Method& m : processed_methods()) {
    int refused_later = 0, clean = 0;
    for (double h : {0.5, 0.75, 1.0, 1.5, 2.0})
      for (double a = 1; a <= 3; a += 0.125) {
        SCOPED_TRACE(std::string(m.name()) + ", h = " + std::to_string(h) +
                     ", q0 = " + std::to_string(a));
        const Vec q0 = Vec::Constant(1, a), p0 = Vec::Zero(1);
        std::optional<Integrator> one;
        if (!error_of([&] { one.emplace(m, quartic(), h, q0, p0, unguarded); }).empty())
          continue;  // (pi^-1 of the start fails: refused at construction)
        const std::string message = step_by_step(*one, steps);
        Integrator batch(m, quartic(), h, q0, p0, unguarded);
        const std::string batch_message = error_of([&] { batch.integrate(double(steps) * h); });
        EXPECT_EQ(batch.statistics().steps, one->statistics().steps);
        EXPECT_EQ(batch.t(), one->t());
        EXPECT_EQ(batch.q(), one->q());
        EXPECT_EQ(batch.p(), one->p());
        if (message.empty()) {
          EXPECT_EQ(batch_message, "");
          ++clean;
          continue;
        }
        const std::string step = "step " + std::to_string(one->statistics().steps + 1) + " (t = ";
        EXPECT_CONTAINS(message, step);
        EXPECT_CONTAINS(batch_message, step);
        if (message.find("processor pi ") == std::string::npos) continue;  // (the kernel failed)
        EXPECT_CONTAINS(batch_message, "processor pi ");
        refused_later += one->statistics().steps > 0;
        const Snapshot before(batch);
        const double t_end = batch.t() + 0.5 * h;
        if (error_of([&] { batch.integrate(t_end); }).empty())
          EXPECT_EQ(batch.t(), t_end);
        else
          before.expect_same(batch);
      }
    EXPECT_GT(refused_later, 0) << m.name() << ": no run reached a state pi cannot map";
    EXPECT_GT(clean, 0) << m.name() << ": no run ended without error";
  }
}

TEST(Processing, TheRegistryHasProcessedMethodsWithTheirKernelsOrders) {
  const std::vector<Method> methods = processed_methods();
  EXPECT_GE(methods.size(), 3u);
  for (const Method& m : methods) {
    EXPECT_TRUE(m.is_explicit()) << m.name();
    EXPECT_LT(m.kernel_order(), m.order()) << m.name();
  }
}

}  // namespace
}  // namespace erkn::test
