// erkn::mpi on 1, 2 and 4 ranks (ctest runs this program under mpirun with each count): the
// distributed integrator agrees with erkn::Integrator on the whole grid to round-off, for every
// method and every boundary; errors on one rank are errors on all; ensembles over ranks are
// bit-identical to one process.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "scenes.hpp"

namespace erkn::test {
namespace {

struct Runs {
  Eigen::VectorXd q_mpi, p_mpi, q_serial, p_serial;
  double H_mpi, H_serial;
  Statistics mpi, serial;
};

// grad U = kappa q + sin q with h^2 abar_ii kappa >> 1: the stages' fixed-point iteration
// diverges, and only Newton(-Krylov) solves them.
System stiff_sine_gordon(const Stiffness& M) {
  System s = sine_gordon(M);
  s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g = 5000 * q.array() + q.array().sin();
  };
  s.potential = [](const Eigen::VectorXd& q) {
    return (2500 * q.array().square() + 1 - q.array().cos()).sum();
  };
  return s;
}

Runs run_both(const Method& method, const Grid& g, double h, int steps,
              System (*system)(const Stiffness&) = sine_gordon) {
  const Scene sc = scene(g);
  mpi::GridIntegrator distributed(MPI_COMM_WORLD, method, system(sc.M), h, sc.q0_slab, sc.p0_slab,
                                  converged());
  Integrator serial(method, system(sc.M), h, sc.q0, sc.p0, converged());
  for (int k = 0; k < steps; ++k) distributed.step(), serial.step();
  return {distributed.gather(distributed.q()),
          distributed.gather(distributed.p()),
          serial.q(),
          serial.p(),
          distributed.energy(),
          serial.energy(),
          distributed.statistics(),
          serial.statistics()};
}

TEST(GridMpi, SlabsPartitionTheGrid) {
  for (const Grid& g : grids()) {
    const Stiffness M = Stiffness::grid(g.axes, g.shift);
    const mpi::Slab s = mpi::slab(MPI_COMM_WORLD, M);
    long sizes = long(s.size), rows = long(s.rows);
    MPI_Allreduce(MPI_IN_PLACE, &sizes, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &rows, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(sizes, M.dim());
    EXPECT_EQ(rows, g.axes[0].n);
  }
}

// Methods with modified kicks are refused (the distributed stepper forms no grad(|grad U|^2)):
// by a collective error on every rank, naming the method.
TEST(GridMpi, RefusesMethodsWithModifiedKicksNamingThem) {
  const Scene sc = scene(grids()[0]);
  int refused = 0;
  for (const Method& method : Method::all()) {
    if (!method.has_modified_kicks()) continue;
    try {
      mpi::GridIntegrator run(MPI_COMM_WORLD, method, sine_gordon(sc.M), 0.1, sc.q0_slab,
                              sc.p0_slab);
      ADD_FAILURE() << method.name() << " not refused";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("modified kicks"), std::string::npos) << e.what();
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
}

// Processed methods (psi = pi o K o pi^-1): the grid integrator has no processor and refuses
// them on every rank, naming the method (those with plain kicks: the test above has the others).
TEST(GridMpi, RefusesProcessedMethodsNamingThem) {
  const Scene sc = scene(grids()[0]);
  int refused = 0;
  for (const Method& method : Method::all()) {
    if (!method.is_processed() || method.has_modified_kicks()) continue;
    try {
      mpi::GridIntegrator run(MPI_COMM_WORLD, method, sine_gordon(sc.M), 0.1, sc.q0_slab,
                              sc.p0_slab);
      ADD_FAILURE() << method.name() << " not refused";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(std::string(method.name()) + " is processed"),
                std::string::npos)
          << e.what();
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
}

TEST(GridMpi, AgreesWithTheSingleProcessIntegratorForEveryMethodAndBoundary) {
  for (const Method& method : Method::all())
    for (const Grid& g : grids()) {
      if (method.has_modified_kicks() || method.is_processed()) continue;  // (refused: above)
      SCOPED_TRACE(std::string(method.name()) + ", grid of " + std::to_string(g.axes.size()) +
                   " axes, " + std::to_string(ranks()) + " ranks");
      const Runs r = run_both(method, g, 0.1, 12);
      EXPECT_LE(max_difference(r.q_mpi, r.q_serial), 1e-13);
      EXPECT_LE(max_difference(r.p_mpi, r.p_serial), 1e-13);
      EXPECT_NEAR(r.H_mpi, r.H_serial, 1e-13 * std::abs(r.H_serial));
      EXPECT_GT(r.q_serial.lpNorm<Eigen::Infinity>(), 0.1);  // (a non-trivial state)
      // An explicit method takes the library's explicit step: its evaluations too (FSAL: s - 1
      // per step where the first kick reuses the last step's force).
      if (method.is_explicit())
        EXPECT_EQ(r.mpi.gradient_evaluations, r.serial.gradient_evaluations);
    }
}

TEST(GridMpi, AnOffGridEndTakesTheSameShorterLastStepAsTheSingleProcessIntegrator) {
  const Scene sc = scene(grids()[1]);
  const Method& method = Method::by_name("SERKN3s4(1)");
  mpi::GridIntegrator distributed(MPI_COMM_WORLD, method, sine_gordon(sc.M), 0.1, sc.q0_slab,
                                  sc.p0_slab, converged());
  Integrator serial(method, sine_gordon(sc.M), 0.1, sc.q0, sc.p0, converged());
  for (double t_end : {0.55, 0.75, 1.0}) {  // off the grid, off the new grid, on it
    distributed.integrate(t_end);
    serial.integrate(t_end);
    EXPECT_EQ(distributed.t(), t_end);
    EXPECT_LE(max_difference(distributed.gather(distributed.q()), serial.q()), 1e-13) << t_end;
  }
  EXPECT_EQ(distributed.statistics().steps, serial.statistics().steps);
  // The one time grid (erkn/time_grid.hpp): within round-off of t() or of a grid point is on it
  // (1 ulp before t(): no step; 1.0 + 0.1 + 0.2: three whole steps, no shorter one).
  for (auto [t_end, steps] : {std::pair{std::nextafter(1.0, 0.0), 0L}, {1.0 + 0.1 + 0.2, 3L}}) {
    const long before = serial.statistics().steps;
    distributed.integrate(t_end);
    serial.integrate(t_end);
    EXPECT_EQ(distributed.t(), serial.t()) << t_end;
    EXPECT_EQ(serial.statistics().steps - before, steps) << t_end;
    EXPECT_EQ(distributed.statistics().steps, serial.statistics().steps) << t_end;
  }
  EXPECT_THROW(distributed.integrate(0.5), Error);  // before t()
}

// d = 288 > 256: one process solves the stages by Newton-Krylov too (the same solver,
// stage_solver.hpp, over one process's space); every rank count agrees with it to round-off.
TEST(GridMpi, NewtonKrylovSolvesStagesTheFixedPointCannotAsOneProcessDoes) {
  const Grid g{{{18, 0.55, B::periodic}, {16, 0.55, B::dirichlet}}, 0.0};
  for (const Method& method : Method::all()) {
    if (method.is_explicit()) continue;  // abar_ii = 0: no stage equation
    SCOPED_TRACE(std::string(method.name()) + ", " + std::to_string(ranks()) + " ranks");
    const Runs r = run_both(method, g, 0.1, 3, stiff_sine_gordon);
    EXPECT_GT(r.mpi.newton_fallbacks, 0);  // (the fixed point alone failed)
    EXPECT_GT(r.serial.newton_fallbacks, 0);
    EXPECT_LE(max_difference(r.q_mpi, r.q_serial), 1e-12);
    EXPECT_LE(max_difference(r.p_mpi, r.p_serial), 1e-12);
    EXPECT_GT(r.q_serial.lpNorm<Eigen::Infinity>(), 0.01);  // (a non-trivial state)
  }
}

// Negative control: without Newton's iterations the same stages fail, on every rank, naming the
// stage, with the state unchanged.
TEST(GridMpi, TheStiffStagesFailWithoutNewtonOnEveryRank) {
  const Grid g{{{18, 0.55, B::periodic}, {16, 0.55, B::dirichlet}}, 0.0};
  const Stiffness M = Stiffness::grid(g.axes, g.shift);
  const mpi::Slab slab = mpi::slab(MPI_COMM_WORLD, M);
  Options o;
  o.max_newton_iterations = 1;
  mpi::GridIntegrator run(MPI_COMM_WORLD, Method::by_name("SERKN2s4"), stiff_sine_gordon(M), 0.1,
                          Eigen::VectorXd::Constant(slab.size, 0.3),
                          Eigen::VectorXd::Constant(slab.size, 0.1), o);
  const Eigen::VectorXd before = run.q();
  std::string message;
  try {
    run.step();
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("stage 1 of SERKN2s4 did not converge"), std::string::npos) << message;
  EXPECT_EQ(run.q(), before);
  EXPECT_EQ(run.statistics().steps, 0);
}

TEST(GridMpi, TheComparisonDetectsADifferentStepSize) {  // negative control
  const Grid g = grids()[1];
  const Runs a = run_both(Method::by_name("SERKN2s4"), g, 0.1, 12);
  const Runs b = run_both(Method::by_name("SERKN2s4"), g, 0.1 * (1 + 1e-6), 12);
  EXPECT_GT(max_difference(a.q_mpi, b.q_serial), 1e-9);
}

// Rank 0's text, on every rank.
std::string rank_0s(std::string text) {
  int length = int(text.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  text.resize(std::size_t(length));
  MPI_Bcast(text.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  return text;
}

// Up to 40 steps of `method` whose gradient on the last rank writes `bad` into the 25th
// evaluation (bad_all: into every entry, else the first); the error (empty: none), the state
// before the step that failed, and the state after.
struct Culprit {
  std::string message;
  Eigen::VectorXd before, after, p_before, p_after;  // (q and p)
  long steps = 0;
};
Culprit run_with_culprit(const Method& method, double bad, bool bad_all) {
  const Grid g = grids()[0];
  const Stiffness M = Stiffness::grid(g.axes, g.shift);
  System sys = sine_gordon(M);
  const bool culprit = rank() == ranks() - 1;
  sys.gradient = [=, calls = 0](const Eigen::VectorXd& q, Eigen::VectorXd& g) mutable {
    g = q.array().sin();
    if (culprit && ++calls == 25 && g.size() > 0) {
      if (bad_all)
        g.setConstant(bad);
      else
        g[0] = bad;
    }
  };
  const mpi::Slab slab = mpi::slab(MPI_COMM_WORLD, M);
  mpi::GridIntegrator run(MPI_COMM_WORLD, method, sys, 0.1,
                          Eigen::VectorXd::Constant(slab.size, 0.3),
                          Eigen::VectorXd::Constant(slab.size, 0.1));
  Culprit c;
  try {
    for (int k = 0; k < 40; ++k) {
      c.before = run.q(), c.p_before = run.p();
      run.step();
    }
  } catch (const Error& e) {
    c.message = e.what();
  }
  c.after = run.q(), c.p_after = run.p();
  c.steps = run.statistics().steps;
  return c;
}

// Every method the distributed integrator runs, implicit (the stage solver's reduce) and
// explicit (the explicit stepper's settle at the end of the step): a gradient non-finite on the
// last rank only (that rank's error), or one so large that the force overflows in eigen
// coordinates (the checks of the explicit passes, deferred), is the same error on every rank,
// with the state before the step kept.
TEST(GridMpi, ANonFiniteGradientOnOneRankIsAnErrorOnEveryRankAndTheStateIsUnchanged) {
  for (const Method& method : Method::all()) {
    if (method.has_modified_kicks() || method.is_processed()) continue;  // (refused: above)
    for (const auto& [bad, all] : {std::pair{std::numeric_limits<double>::infinity(), false},
                                   std::pair{std::numeric_limits<double>::max(), true}}) {
      SCOPED_TRACE(std::string(method.name()) + (all ? ", overflow" : ", inf"));
      const Culprit c = run_with_culprit(method, bad, all);
      // (the stage solver's words for a non-finite stage; the checks' for a force or a p)
      EXPECT_TRUE(c.message.find("not finite") != std::string::npos ||
                  c.message.find("non-finite") != std::string::npos)
          << c.message;
      if (ranks() > 1 && !all)  // (an overflow in eigen coordinates reaches every rank's part)
        EXPECT_NE(c.message.find("rank " + std::to_string(ranks() - 1)), std::string::npos)
            << c.message;
      EXPECT_EQ(c.after, c.before);
      EXPECT_EQ(c.p_after, c.p_before);
      EXPECT_GT(c.steps, 0);
      EXPECT_EQ(c.message, rank_0s(c.message));  // (every rank's: the same)
    }
  }
}

// Negative control: a large but harmless value in the same place is no error (40 steps).
TEST(GridMpi, AFiniteGradientValueInThatPlaceIsNoError) {
  for (const Method& method : Method::all()) {
    if (method.has_modified_kicks() || method.is_processed()) continue;
    SCOPED_TRACE(method.name());
    const Culprit c = run_with_culprit(method, 10.0, false);
    EXPECT_EQ(c.message, "");
    EXPECT_EQ(c.steps, 40);
  }
}

TEST(GridMpi, AGradientThatThrowsOnOneRankIsAnErrorOnEveryRank) {
  const Grid g = grids()[0];
  const Stiffness M = Stiffness::grid(g.axes, g.shift);
  System sys = sine_gordon(M);
  const bool culprit = rank() == 0;
  sys.gradient = [culprit, calls = 0](const Eigen::VectorXd& q, Eigen::VectorXd& g) mutable {
    if (culprit && ++calls == 9) throw std::runtime_error("table lookup out of range");
    g = q.array().sin();
  };
  const mpi::Slab slab = mpi::slab(MPI_COMM_WORLD, M);
  mpi::GridIntegrator run(MPI_COMM_WORLD, Method::by_name("SERKN2s4"), sys, 0.1,
                          Eigen::VectorXd::Constant(slab.size, 0.3),
                          Eigen::VectorXd::Constant(slab.size, 0.1));
  std::string message;
  try {
    run.integrate(1.0);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("threw: table lookup out of range"), std::string::npos) << message;
  run.integrate(run.t() + 0.1);  // (the callback works again: every rank is still in step)
}

TEST(GridMpi, BadInputIsRefusedOnEveryRank) {
  const Grid g = grids()[0];
  const Stiffness M = Stiffness::grid(g.axes, g.shift);
  const mpi::Slab slab = mpi::slab(MPI_COMM_WORLD, M);
  const Method& m = Method::by_name("SERKN2s4");
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(slab.size);
  // A wrong size on rank 0 only.
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(slab.size + (rank() == 0 ? 1 : 0));
  EXPECT_THROW(mpi::GridIntegrator(MPI_COMM_WORLD, m, sine_gordon(M), 0.1, q0, z), Error);
  EXPECT_THROW(mpi::GridIntegrator(MPI_COMM_WORLD, m, sine_gordon(M), -0.1, z, z), Error);
  EXPECT_THROW(mpi::GridIntegrator(MPI_COMM_WORLD, m, sine_gordon(Stiffness::scalar(1)), 0.1, z, z),
               Error);
  const Stiffness line = Stiffness::grid({{16, 0.5, B::periodic}});
  EXPECT_THROW(mpi::slab(MPI_COMM_WORLD, line), Error);
  // Still usable afterwards: no rank is stuck in a collective call.
  mpi::GridIntegrator ok(MPI_COMM_WORLD, m, sine_gordon(M), 0.1, z, z);
  ok.integrate(0.5);
  EXPECT_DOUBLE_EQ(ok.t(), 0.5);
}

Member pendulum(std::size_t i) {
  Member m;
  m.system.M = Stiffness::scalar(1 + 0.1 * double(i));
  m.system.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().sin(); };
  m.q0 = Eigen::VectorXd::Constant(2, 0.1 * double(i));
  m.p0 = Eigen::VectorXd::Constant(2, i == 5 ? std::numeric_limits<double>::quiet_NaN() : 0.5);
  return m;
}

TEST(GridMpi, AnEnsembleOverRanksIsBitIdenticalToOneProcess) {
  const Ensemble ensemble(Method::by_name("SERKN3s4(2)"), 0.05, 11, pendulum);
  const auto distributed = mpi::integrate(MPI_COMM_WORLD, ensemble, 2.0, 2);
  const auto local = ensemble.integrate(2.0, 1);
  ASSERT_EQ(distributed.size(), local.size());
  for (std::size_t i = 0; i < local.size(); ++i) {
    EXPECT_EQ(distributed[i].q, local[i].q) << i;
    EXPECT_EQ(distributed[i].p.size(), local[i].p.size()) << i;
    EXPECT_EQ(distributed[i].t, local[i].t) << i;
    EXPECT_EQ(distributed[i].error, local[i].error) << i;
    EXPECT_EQ(distributed[i].statistics.gradient_evaluations,
              local[i].statistics.gradient_evaluations);
  }
  EXPECT_FALSE(distributed[5].ok());  // (p0 is NaN)
  EXPECT_TRUE(distributed[10].ok());
}

}  // namespace
}  // namespace erkn::test

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  // Every rank checks the same gathered results; rank 0 reports.
  if (erkn::test::rank() != 0)
    delete ::testing::UnitTest::GetInstance()->listeners().Release(
        ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  int failed = RUN_ALL_TESTS();
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return failed;
}
