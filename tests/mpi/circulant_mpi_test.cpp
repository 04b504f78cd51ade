// erkn::mpi with a circulant M (distributed_transform.hpp's second form of M, FFTW-MPI's 1-D DFT)
// on 1, 2 and 4 ranks: the blocks partition the vector, and the distributed integrator agrees
// with erkn::Integrator on the whole vector to round-off for every method it runs.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scenes.hpp"

namespace erkn::test {
namespace {

// A 1-D periodic operator that is not a grid's stencil: the 3-point Laplacian (spacing 0.55, as
// the grid tests: h^2 lambda <= 0.2 at h = 0.1, below every pole), a mass 0.3 and a coupling to
// the third neighbours (lambda_k = (2 - 2 cos t) / dx^2 + 0.3 + 0.2 cos 3t >= 0.1).
Stiffness circulant(Eigen::Index n, double coupling = 0.1) {
  const double dx = 0.55;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(n);
  col[0] = 2 / (dx * dx) + 0.3;
  col[1] = col[n - 1] = -1 / (dx * dx);
  col[3] = col[n - 3] = coupling;
  return Stiffness::circulant(col);
}

struct Compared {
  double q = 0, p = 0, H = 0;  // max relative differences
  double size = 0;             // max |q| of the single-process run
};

// 12 steps of `method` distributed over M and in one process over M_serial (M itself but for a
// negative control), from a smooth state of the global index.
Compared compare(const Method& method, const Stiffness& M, const Stiffness& M_serial) {
  const Eigen::Index n = M.dim();
  Eigen::VectorXd q0, p0;
  initial(n, q0, p0);
  const mpi::Slab block = mpi::slab(MPI_COMM_WORLD, M);
  mpi::GridIntegrator distributed(MPI_COMM_WORLD, method, sine_gordon(M), 0.1,
                                  q0.segment(block.first, block.size),
                                  p0.segment(block.first, block.size), converged());
  Integrator serial(method, sine_gordon(M_serial), 0.1, q0, p0, converged());
  for (int k = 0; k < 12; ++k) distributed.step(), serial.step();
  const double H = distributed.energy();
  return {max_difference(distributed.gather(distributed.q()), serial.q()),
          max_difference(distributed.gather(distributed.p()), serial.p()),
          std::abs(H - serial.energy()) / std::abs(serial.energy()),
          serial.q().lpNorm<Eigen::Infinity>()};
}

TEST(CirculantMpi, BlocksPartitionTheVectorInOrder) {
  for (Eigen::Index n : {64, 96}) {
    const mpi::Slab block = mpi::slab(MPI_COMM_WORLD, circulant(n));
    EXPECT_EQ(block.rows, block.size);
    int ranks = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    std::vector<long> firsts(static_cast<size_t>(ranks)), sizes(static_cast<size_t>(ranks));
    const long first = long(block.first), size = long(block.size);
    MPI_Allgather(&first, 1, MPI_LONG, firsts.data(), 1, MPI_LONG, MPI_COMM_WORLD);
    MPI_Allgather(&size, 1, MPI_LONG, sizes.data(), 1, MPI_LONG, MPI_COMM_WORLD);
    long next = 0;  // each block starts where the previous one ends; together: all n entries
    for (int r = 0; r < ranks; ++r) {
      if (sizes[size_t(r)] > 0) EXPECT_EQ(firsts[size_t(r)], next) << "rank " << r;
      next += sizes[size_t(r)];
    }
    EXPECT_EQ(next, n);
  }
}

TEST(CirculantMpi, AgreesWithTheSingleProcessIntegratorForEveryMethod) {
  const Stiffness M = circulant(64);
  int compared = 0;
  for (const Method& method : Method::all()) {
    if (method.has_modified_kicks() || method.is_processed()) continue;  // (refused: grid tests)
    SCOPED_TRACE(std::string(method.name()));
    const Compared c = compare(method, M, M);
    EXPECT_LE(c.q, 1e-13);
    EXPECT_LE(c.p, 1e-13);
    EXPECT_LE(c.H, 1e-13);
    EXPECT_GT(c.size, 0.1);  // (a non-trivial state)
    ++compared;
  }
  EXPECT_GT(compared, 30);
}

// Negative control: the comparison sees a change of the third-neighbour coupling by 1e-6.
TEST(CirculantMpi, TheComparisonDetectsADifferentOperator) {
  const Compared c =
      compare(Method::by_name("SERKN3s4(1)"), circulant(64), circulant(64, 0.1 + 1e-6));
  EXPECT_GT(c.q, 1e-9);
}

}  // namespace
}  // namespace erkn::test
