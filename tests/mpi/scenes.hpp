// The grids, systems, initial states and comparisons the erkn::mpi tests share (grid_mpi_test.cpp,
// circulant_mpi_test.cpp, guard_mpi_test.cpp; one program, run by ctest under mpirun on 1, 2 and 4
// ranks).
#pragma once

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <erkn/mpi.hpp>
#include <vector>

namespace erkn::test {

using B = GridAxis::Boundary;

inline int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
inline int ranks() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// Uneven sizes (7 and 6 rows over 2 or 4 ranks), every boundary, and a mass shift. Spacing 0.55
// keeps h^2 lambda <= 0.45 at h = 0.1, below every method's poles. All-periodic grids (the first
// and the last: 2-D, and 3-D with an odd last axis and a shift) take the real-to-complex
// transform (periodic_slab_transform.hpp), the others the real-to-real one.
struct Grid {
  std::vector<GridAxis> axes;
  double shift;
};
inline std::vector<Grid> grids() {
  return {{{{8, 0.55, B::periodic}, {6, 0.55, B::periodic}}, 0.0},
          {{{7, 0.55, B::dirichlet}, {6, 0.55, B::neumann}, {5, 0.55, B::periodic}}, 0.5},
          {{{6, 0.55, B::neumann}, {7, 0.55, B::dirichlet}}, 0.0},
          {{{5, 0.55, B::periodic}, {6, 0.55, B::periodic}, {5, 0.55, B::periodic}}, 0.25}};
}

inline System sine_gordon(const Stiffness& M) {
  System s;
  s.M = M;
  s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().sin(); };
  s.potential = [](const Eigen::VectorXd& q) { return (1 - q.array().cos()).sum(); };
  return s;
}

// The whole initial state (a smooth function of the global index).
inline void initial(Eigen::Index d, Eigen::VectorXd& q, Eigen::VectorXd& p) {
  q.resize(d), p.resize(d);
  for (Eigen::Index k = 0; k < d; ++k) {
    q[k] = 1.5 * std::sin(0.37 * double(k) + 0.2);
    p[k] = 0.8 * std::cos(0.23 * double(k));
  }
}

// A grid's M with the whole initial state and this rank's slab of it.
struct Scene {
  Stiffness M;
  Eigen::VectorXd q0, p0;            // the whole grid
  Eigen::VectorXd q0_slab, p0_slab;  // this rank's rows
};
inline Scene scene(const Grid& g) {
  Scene s{Stiffness::grid(g.axes, g.shift), {}, {}, {}, {}};
  initial(s.M.dim(), s.q0, s.p0);
  const mpi::Slab slab = mpi::slab(MPI_COMM_WORLD, s.M);
  const Eigen::Index offset = slab.size == 0 ? 0 : slab.first * (s.M.dim() / g.axes[0].n);
  s.q0_slab = s.q0.segment(offset, slab.size);
  s.p0_slab = s.p0.segment(offset, slab.size);
  return s;
}

// Both integrators solve every stage to round-off (a tolerance below it: the iterations stop when
// they stall at round-off), so the comparison sees the method, not where the two stage solvers'
// different starting guesses and stopping tests happen to stop within the default tolerance.
inline Options converged() {
  Options o;
  o.tolerance = 1e-17;
  o.max_fixed_point_iterations = 60;
  return o;
}

inline double max_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(1.0, b.lpNorm<Eigen::Infinity>());
}

}  // namespace erkn::test
