#include "scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>

namespace erkn::mpi::scene {
std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, sep);) parts.push_back(part);
  return parts;
}

namespace {

using Boundary = GridAxis::Boundary;

// Coordinate of point j of an axis on [-1, 1] (periodic: nodes from -1; Dirichlet: interior
// nodes; Neumann: cell centres).
double coordinate(const GridAxis& a, Eigen::Index j) {
  switch (a.boundary) {
    case Boundary::periodic:
      return -1 + double(j) * a.spacing;
    case Boundary::dirichlet:
      return -1 + double(j + 1) * a.spacing;
    case Boundary::neumann:
      return -1 + (double(j) + 0.5) * a.spacing;
  }
  return 0;
}

}  // namespace

std::vector<GridAxis> parse_axes(const std::string& grid, const std::string& boundaries) {
  const std::vector<std::string> n = split(grid, 'x'), b = split(boundaries, ',');
  if (n.size() < 2) throw Error("--grid needs two or more axes, like 256x256");
  if (b.size() != 1 && b.size() != n.size())
    throw Error("--boundary needs one name or one per axis");
  std::vector<GridAxis> axes;
  for (std::size_t a = 0; a < n.size(); ++a) {
    std::size_t used = 0;
    long size = 0;
    try {
      size = std::stol(n[a], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != n[a].size() || size < 2)
      throw Error("--grid " + grid + ": every axis needs a whole number of points >= 2");
    const Boundary kind = GridAxis::boundary_named(b.size() == 1 ? b[0] : b[a]);
    const double spacing = 2.0 / double(kind == Boundary::dirichlet ? size + 1 : size);
    axes.push_back({Eigen::Index(size), spacing, kind});
  }
  return axes;
}

std::string describe(const std::vector<GridAxis>& axes) {
  std::string s;
  for (const GridAxis& a : axes) s += (s.empty() ? "" : "x") + std::to_string(a.n);
  return s;
}

namespace {

// The Gaussian bump exp(-8|x|^2) on the unknowns first .. first + size - 1 of the grid
// (row-major, axis 0 slowest): a rank's slab, or the whole grid.
Eigen::VectorXd bump(const std::vector<GridAxis>& axes, Eigen::Index first, Eigen::Index size) {
  Eigen::VectorXd q0(size);
  for (Eigen::Index k = 0; k < size; ++k) {
    Eigen::Index rest = k;
    double r2 = 0;
    for (std::size_t a = axes.size(); a-- > 1;) {
      const double x = coordinate(axes[a], rest % axes[a].n);
      r2 += x * x, rest /= axes[a].n;
    }
    const double x0 = coordinate(axes[0], first + rest);
    r2 += x0 * x0;
    q0[k] = 2 * std::exp(-8 * r2);
  }
  return q0;
}

System sine_gordon(const Stiffness& M) {
  System sys;
  sys.M = M;
  sys.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().sin(); };
  sys.potential = [](const Eigen::VectorXd& q) { return (1 - q.array().cos()).sum(); };
  return sys;
}

Options options(const Settings& s) {
  Options o;
  o.blowup_guard = s.guard;
  return o;
}

// One timed block of s.steps steps: wall, transform and CPU seconds, transforms executed.
struct Block {
  double wall = 0, transform_seconds = 0, cpu = 0;
  long transforms = 0;
};

// The energy drift and the best of s.repeats blocks (take() runs one) after one warm-up step.
template <class Run, class Take>
Timing timed(Run& run, const Settings& s, Take take) {
  Timing t;
  const double H0 = run.energy();
  run.step();  // warm-up
  t.seconds_per_step = 1e300;
  for (int r = 0; r < s.repeats; ++r) {
    const Statistics before = run.statistics();
    const Block b = take();
    if (b.wall / s.steps < t.seconds_per_step) {
      t.seconds_per_step = b.wall / s.steps;
      t.transform_seconds_per_step = b.transform_seconds / s.steps;
      t.cpu_seconds_per_step = b.cpu / s.steps;
    }
    t.transforms_per_step = double(b.transforms) / s.steps;
    t.gradients_per_step =
        double(run.statistics().gradient_evaluations - before.gradient_evaluations) / s.steps;
  }
  t.energy_drift = std::abs(run.energy() - H0) / std::abs(H0);
  std::ifstream("/proc/loadavg") >> t.load;
  return t;
}

}  // namespace

Timing run(MPI_Comm comm, const Settings& s) {
  const Stiffness M = Stiffness::grid(s.axes, s.shift);
  const Slab slab = mpi::slab(comm, M);
  const Eigen::VectorXd q0 = bump(s.axes, slab.first, slab.size);
  GridIntegrator run(comm, Method::by_name(s.method), sine_gordon(M), s.h, q0,
                     Eigen::VectorXd::Zero(slab.size), options(s));
  Timing t = timed(run, s, [&] {  // (times of the slowest rank)
    const long transforms = run.transforms();
    const double transform_seconds = run.transform_seconds();
    MPI_Barrier(comm);
    const double start = MPI_Wtime();
    const std::clock_t cpu_start = std::clock();
    run.integrate(run.t() + s.steps * s.h);  // (what a user calls: the state loaded once)
    std::array<double, 3> times{MPI_Wtime() - start, run.transform_seconds() - transform_seconds,
                                double(std::clock() - cpu_start) / CLOCKS_PER_SEC};
    MPI_Allreduce(MPI_IN_PLACE, times.data(), 3, MPI_DOUBLE, MPI_MAX, comm);
    return Block{times[0], times[1], times[2], run.transforms() - transforms};
  });
  MPI_Comm_size(comm, &t.ranks);
  t.d = long(M.dim());
  std::array<double, 2> sums{run.q().sum(), run.q().squaredNorm()};
  MPI_Allreduce(MPI_IN_PLACE, sums.data(), 2, MPI_DOUBLE, MPI_SUM, comm);
  t.sum_q = sums[0], t.norm_q = std::sqrt(sums[1]);
  return t;
}

Timing run_serial(const Settings& s) {
  const Stiffness M = Stiffness::grid(s.axes, s.shift);
  Integrator run(Method::by_name(s.method), sine_gordon(M), s.h, bump(s.axes, 0, M.dim()),
                 Eigen::VectorXd::Zero(M.dim()), options(s));
  Timing t = timed(run, s, [&] {  // (transforms not counted)
    const double start = MPI_Wtime();
    const std::clock_t cpu_start = std::clock();
    run.step(s.steps);  // (what a serial user calls: the state loaded once, by q())
    run.q();
    return Block{MPI_Wtime() - start, 0, double(std::clock() - cpu_start) / CLOCKS_PER_SEC, 0};
  });
  t.d = long(M.dim());
  t.sum_q = run.q().sum(), t.norm_q = run.q().norm();
  return t;
}

}  // namespace erkn::mpi::scene
