// erkn::mpi (optional component erkn::mpi; needs MPI and FFTW-MPI): beyond one machine.
//
// GridIntegrator integrates q'' + M q = -grad U(q) for M = Stiffness::grid (two or more axes)
// with the state distributed in slabs along axis 0 over the ranks of a communicator (FFTW-MPI's
// layout), or for M = Stiffness::circulant (a 1-D periodic operator) with the vector distributed
// in contiguous blocks (FFTW-MPI's 1-D DFT; slab() says which entries a rank owns). Per step the
// only communication is the transforms into M's eigenbasis (FFTW-MPI, transposed output: one
// all-to-all per transform) and one MPI_Allreduce per stage iteration (the stage solver's norms);
// the coefficients act on each rank's spectral rows and grad U on each rank's slab. The step is eq.
// (d) of the paper with erkn::Integrator's stage solver (runtime/src/stage_solver.hpp, the same
// code over a distributed space): fixed-point iteration from predicted starting values, with its
// first-iteration stop, and matrix-free Newton-Krylov where it fails, every norm and dot product
// summed over the ranks. With the stages solved to round-off the result agrees with
// erkn::Integrator's on the whole grid to round-off (the sums over the ranks and FFTW-MPI round
// differently); at the default tolerance the two differ by about that tolerance. An explicit
// method (every abar_ii = 0: Strang, SABA_n, SD9(10,6,4), ...) steps with erkn::Integrator's
// explicit stepper (flows and kicks, the last force reused where the method allows) over the same
// distributed space, its checks one MPI_Allreduce per step; it agrees with erkn::Integrator to
// round-off.
//
// The System's callbacks see the rank's slab: gradient must be pointwise (grad U(q)_j depends on
// q_j only, as for sine-Gordon or phi^4), and potential returns the slab's part of U (the
// integrator sums the parts). Every call below is collective over the communicator; an error on
// any rank is thrown on every rank, with the same message.
//
// The blow-up guard (Options::blowup_guard, on by default) is erkn::Integrator's, its sums
// (1/2|p|^2 + 1/2 q'M q and U) reduced over the ranks in one MPI_Allreduce every 1024 steps: an
// energy error |H - H_0| beyond a quarter of 1/2|p0|^2 + 1/2 q0'M q0 + |U(q0)| (with
// System::potential), else a 1e4-fold growth of 1/2|p|^2 + 1/2 q'M q, or a non-finite state
// stops the run on every rank with the same erkn::Error naming the time, the growth and the
// likely cause, and keeps the state of the last check that passed (q(), p(), t(),
// statistics().steps). The likely cause is the step-size advisor's linear model at h
// (erkn/advisor.hpp) at the kept state: M's eigenvalues, the Hessian of the pointwise U
// (diagonal: one more gradient) and the state's mode energies, without the trial run
// erkn::Integrator's guard adds (it would integrate the whole grid on one process).
// Options::blowup_guard = false switches it off.
//
// A complete program (2-D sine-Gordon; link with erkn::mpi, run with mpirun -np N):
//
//   #include <cmath>
//   #include <cstdio>
//   #include <erkn/mpi.hpp>
//
//   int main(int argc, char** argv) {
//     MPI_Init(&argc, &argv);
//     int rank = 0, status = 0;
//     MPI_Comm_rank(MPI_COMM_WORLD, &rank);
//     {  // (the integrator must be gone before MPI_Finalize)
//       using B = erkn::GridAxis::Boundary;
//       const int n = 64;  // periodic n x n grid on the square of side 2, spacing 2/n
//       const erkn::Stiffness M =
//           erkn::Stiffness::grid({{n, 2.0 / n, B::periodic}, {n, 2.0 / n, B::periodic}});
//       const erkn::mpi::Slab slab = erkn::mpi::slab(MPI_COMM_WORLD, M);  // this rank's rows
//       Eigen::VectorXd q0(slab.size), p0 = Eigen::VectorXd::Zero(slab.size);
//       for (Eigen::Index r = 0; r < slab.rows; ++r)
//         for (Eigen::Index j = 0; j < n; ++j) {
//           const double x = -1 + 2.0 * double(slab.first + r) / n, y = -1 + 2.0 * double(j) / n;
//           q0[r * n + j] = 2 * std::exp(-8 * (x * x + y * y));
//         }
//       erkn::System sys;
//       sys.M = M;
//       sys.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().sin(); };
//       sys.potential = [](const Eigen::VectorXd& q) { return (1 - q.array().cos()).sum(); };
//       erkn::mpi::GridIntegrator run(MPI_COMM_WORLD, erkn::Method::by_name("SERKN2s4"), sys,
//                                     0.01, q0, p0);
//       const double H0 = run.energy();
//       run.integrate(1.0);
//       const double drift = std::abs(run.energy() - H0) / H0;
//       if (rank == 0) std::printf("|H(1) - H(0)| / H(0) = %.1e\n", drift);
//       status = drift < 1e-6 ? 0 : 1;
//     }
//     MPI_Finalize();
//     return status;
//   }
#pragma once

#include <mpi.h>

#include <Eigen/Core>
#include <erkn/erkn.hpp>
#include <memory>
#include <string>
#include <vector>

namespace erkn::mpi {

/// The part of a grid one rank owns: rows first..first+rows-1 of axis 0 with all of the other
/// axes, `size` unknowns in row-major order (rows may be 0 when there are more ranks than rows);
/// of a circulant M's vector: entries first..first+size-1 (rows = size).
struct Slab {
  Eigen::Index first = 0, rows = 0, size = 0;
};

/// This rank's slab of the grid or circulant M (collective).
Slab slab(MPI_Comm comm, const Stiffness& M);

namespace detail {
class GridStepper;
}

class GridIntegrator {
 public:
  /// q0, p0: this rank's slab. Validates everything on every rank (sizes, finiteness, h > 0,
  /// poles) and plans the transforms.
  GridIntegrator(MPI_Comm comm, const Method& method, System system, double h,
                 const Eigen::VectorXd& q0, const Eigen::VectorXd& p0, const Options& options = {});
  ~GridIntegrator();
  GridIntegrator(GridIntegrator&&) noexcept;
  GridIntegrator& operator=(GridIntegrator&&) noexcept;

  /// One step of h (under the blow-up guard, see above).
  void step();
  /// Steps to t_end as Integrator::integrate does: whole steps of h to the last grid point before
  /// t_end, then (off the grid) one shorter step with the method's coefficients at its size; the
  /// blow-up guard stops it as step() does. Between its steps the state stays in M's eigenbasis
  /// (a step transforms only its stages; step() in a loop also loads the physical state after
  /// each step: two more transforms).
  void integrate(double t_end);

  /// This rank's slab of the state.
  const Eigen::VectorXd& q() const;
  const Eigen::VectorXd& p() const;
  double t() const;
  double h() const;
  const Slab& slab() const;
  /// This rank's counts (the same on every rank: the stage decisions are collective).
  const Statistics& statistics() const;
  /// Distributed transforms so far (each one all-to-all).
  long transforms() const;
  /// Wall time this rank spent in them (including the all-to-all waits).
  double transform_seconds() const;
  /// H(q, p) over the whole grid; needs System::potential (the slab's part of U).
  double energy();
  /// The whole vector from every rank's slab, on every rank (for output and tests).
  Eigen::VectorXd gather(const Eigen::VectorXd& local) const;

 private:
  std::unique_ptr<detail::GridStepper> stepper_;
};

/// The trajectories of an ensemble distributed over the ranks of comm (contiguous blocks, each on
/// `threads` threads per rank, 0: one per hardware thread) and all results on every rank, in
/// trajectory order and bit-identical to Ensemble::integrate in one process.
std::vector<TrajectoryResult> integrate(MPI_Comm comm, const Ensemble& ensemble, double t_end,
                                        int threads = 0);

}  // namespace erkn::mpi
