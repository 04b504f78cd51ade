// The blow-up guard of the distributed integrator (Options::blowup_guard, on by default; the
// mechanism of erkn::Integrator, runtime/src/blowup_guard.hpp, its sums reduced over the ranks):
// a blow-up stops on every rank with the same erkn::Error at the same check as erkn::Integrator
// on the whole grid, keeping the last good state; without a potential the growth of
// 1/2|p|^2 + 1/2 q'M q is caught. Negative controls: with the guard off the same run blows up
// quietly, and a run at a stable h is not stopped and is bit-identical to one without the guard.
// On grids and on a circulant M.
#include <gtest/gtest.h>

#include <numbers>
#include <optional>
#include <string>

#include "scenes.hpp"

namespace erkn::test {
namespace {

constexpr long kCheck = 1024;  // steps between the guard's checks (blowup_guard.hpp)

// The first explicit method of the registry the distributed integrator runs (plain kicks, not
// processed), and the point (V, z) of its stability matrix (erkn/stability.hpp) with the largest
// spectral radius for h sqrt(lambda) in [pi / 2, pi) at z = 0.1: an unstable band of the method,
// not of the equation (z > 0: the test equation is bounded).
struct Band {
  Method method;
  double V = 0, z = 0.1, rho = 1;
};
Band unstable_band() {
  std::optional<Method> chosen;
  for (const Method& m : Method::all())
    if (m.is_explicit() && !m.has_modified_kicks() && !m.is_processed() && !chosen) chosen = m;
  Band b{*chosen, 0, 0.1, 1};
  for (int k = 0; k < 4000; ++k) {
    const double theta = std::numbers::pi * (0.5 + 0.5 * k / 4000.0);
    const double rho = stability_matrix(b.method, theta * theta, b.z).spectral_radius();
    if (rho > b.rho) b.rho = rho, b.V = theta * theta;
  }
  return b;
}

// grad U = kappa q (pointwise), U = kappa/2 |q|^2 (each rank's part).
System linear_force(const Stiffness& M, double kappa, bool with_potential = true) {
  System s;
  s.M = M;
  s.gradient = [kappa](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = kappa * q; };
  if (with_potential)
    s.potential = [kappa](const Eigen::VectorXd& q) { return 0.5 * kappa * q.squaredNorm(); };
  return s;
}

// The step size putting M's largest eigenvalue at V, and kappa = z / h^2.
struct Setting {
  double h, kappa;
};
Setting setting(const Stiffness& M, double V, double z) {
  const double h = std::sqrt(V / M.eigenvalues().maxCoeff());
  return {h, z / (h * h)};
}

Options guarded(bool on) {
  Options o;
  o.blowup_guard = on;
  return o;
}

// The message on rank 0, on every rank.
std::string rank0(std::string message) {
  int length = int(message.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  message.resize(std::size_t(length));
  MPI_Bcast(message.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  return message;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The message of the erkn::Error that stops run.integrate(t_end) ("" when none does).
std::string stop_message(mpi::GridIntegrator& run, double t_end) {
  try {
    run.integrate(t_end);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// grad U = -q / 100 without a potential: the equation itself grows (M's zero eigenvalue: rate 0.1,
// the zero mode's E_2 like e^(0.2 t)); the guard stops it at a check, after a 1e4-fold growth of
// E_2, with the same message on every rank, and the likely cause says so.
void expect_the_equations_growth_caught(const Stiffness& M, const Eigen::VectorXd& q0_slab,
                                        const Eigen::VectorXd& p0_slab) {
  const double h = 0.1;
  mpi::GridIntegrator run(MPI_COMM_WORLD, unstable_band().method, linear_force(M, -0.01, false), h,
                          q0_slab, p0_slab);
  const std::string message = stop_message(run, 4 * kCheck * h);
  EXPECT_TRUE(has(message, "grew by a factor")) << message;
  EXPECT_TRUE(has(message, "Likely cause: the differential equation's own growth")) << message;
  EXPECT_EQ(rank0(message), message);
  EXPECT_EQ(run.statistics().steps % kCheck, 0);
}

TEST(GridMpiGuard, ABlowUpStopsOnEveryRankAtTheCheckTheSingleProcessGuardStopsAt) {
  const Band b = unstable_band();
  ASSERT_GT(b.rho, 1.005) << b.method.name();  // (growth rho^1024 > 1e2 per check)
  const Scene sc = scene(grids()[0]);
  const Setting s = setting(sc.M, b.V, b.z);
  SCOPED_TRACE(std::string(b.method.name()) + ", h = " + std::to_string(s.h) + ", " +
               std::to_string(ranks()) + " ranks");
  mpi::GridIntegrator run(MPI_COMM_WORLD, b.method, linear_force(sc.M, s.kappa), s.h, sc.q0_slab,
                          sc.p0_slab);
  const double H0 = run.energy();
  const std::string message = stop_message(run, 4 * kCheck * s.h);
  EXPECT_TRUE(has(message, "blow-up guard: at t = ")) << message;
  EXPECT_TRUE(has(message, "the energy error")) << message;
  EXPECT_TRUE(has(message, "Likely cause: the step size, by the step-size advisor")) << message;
  EXPECT_TRUE(has(message, "Options::blowup_guard = false")) << message;
  EXPECT_EQ(rank0(message), message);  // (the same on every rank)
  // The state of the last check that passed is kept: a good one, on a check's step.
  EXPECT_EQ(run.statistics().steps % kCheck, 0);
  EXPECT_LT(run.statistics().steps, 4 * kCheck);
  EXPECT_LE(std::abs(run.energy() - H0), 0.25 * std::abs(H0));
  // erkn::Integrator on the whole grid stops at the same check and keeps the same state.
  Integrator serial(b.method, linear_force(sc.M, s.kappa), s.h, sc.q0, sc.p0);
  EXPECT_THROW(serial.integrate(4 * kCheck * s.h), Error);
  EXPECT_EQ(serial.statistics().steps, run.statistics().steps);
  EXPECT_EQ(serial.t(), run.t());
  EXPECT_LE((run.gather(run.q()) - serial.q()).lpNorm<Eigen::Infinity>(),
            1e-10 * serial.q().lpNorm<Eigen::Infinity>());
}

// Negative control: the guard is what stops it. Off, the same run ends quietly with an energy
// error far beyond the guard's limit.
TEST(GridMpiGuard, WithoutTheGuardTheSameRunBlowsUpQuietly) {
  const Band b = unstable_band();
  const Scene sc = scene(grids()[0]);
  const Setting s = setting(sc.M, b.V, b.z);
  mpi::GridIntegrator run(MPI_COMM_WORLD, b.method, linear_force(sc.M, s.kappa), s.h, sc.q0_slab,
                          sc.p0_slab, guarded(false));
  const double H0 = run.energy();
  EXPECT_NO_THROW(run.integrate(2 * kCheck * s.h));
  EXPECT_EQ(run.statistics().steps, 2 * kCheck);
  EXPECT_GT(std::abs(run.energy() - H0), 1e3 * std::abs(H0));
}

// Negative control: at a stable h (h sqrt(lambda_max) = pi / 2, z = 0.1) the guard checks twice,
// passes, and changes nothing: the run is bit-identical to one without it.
TEST(GridMpiGuard, ARunAtAStableStepSizeIsNotStoppedAndNotChanged) {
  const Band b = unstable_band();
  const Scene sc = scene(grids()[0]);
  const Setting s = setting(sc.M, std::pow(std::numbers::pi / 2, 2), b.z);
  ASSERT_LT(stability_matrix(b.method, std::pow(std::numbers::pi / 2, 2), b.z).spectral_radius(),
            1 + 1e-12);
  mpi::GridIntegrator on(MPI_COMM_WORLD, b.method, linear_force(sc.M, s.kappa), s.h, sc.q0_slab,
                         sc.p0_slab, guarded(true));
  mpi::GridIntegrator off(MPI_COMM_WORLD, b.method, linear_force(sc.M, s.kappa), s.h, sc.q0_slab,
                          sc.p0_slab, guarded(false));
  EXPECT_NO_THROW(on.integrate(2 * kCheck * s.h + 0.5 * s.h));  // (and a shorter last step)
  off.integrate(2 * kCheck * s.h + 0.5 * s.h);
  EXPECT_EQ(on.statistics().steps, 2 * kCheck + 1);
  EXPECT_EQ(on.q(), off.q());
  EXPECT_EQ(on.p(), off.p());
  EXPECT_EQ(on.t(), off.t());
}

// Without System::potential the guard watches 1/2|p|^2 + 1/2 q'M q: grad U = -q / 100 makes the
// equation itself grow (M's zero eigenvalue on the periodic grid: rate 0.1), which the guard
// stops after a 1e4-fold growth, and the likely cause says so.
TEST(GridMpiGuard, WithoutAPotentialTheGrowthOfTheStateIsCaught) {
  const Scene sc = scene(grids()[0]);
  expect_the_equations_growth_caught(sc.M, sc.q0_slab, sc.p0_slab);
}

// The same guard with a circulant M (the other form the distributed integrator takes): a 3-point
// Laplacian on 64 points (spacing 0.55, lambda_0 = 0) and the equation's growth as above.
TEST(GridMpiGuard, OnACirculantMTheGrowthIsCaughtAlike) {
  const Eigen::Index n = 64;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(n), q0(n), p0(n);
  col[0] = 2 / (0.55 * 0.55), col[1] = col[n - 1] = -1 / (0.55 * 0.55);
  initial(n, q0, p0);
  const Stiffness M = Stiffness::circulant(col);
  const mpi::Slab block = mpi::slab(MPI_COMM_WORLD, M);
  expect_the_equations_growth_caught(M, q0.segment(block.first, block.size),
                                     p0.segment(block.first, block.size));
}

}  // namespace
}  // namespace erkn::test
