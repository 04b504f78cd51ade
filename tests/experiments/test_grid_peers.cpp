// The experiments' grid M (LinearPart::grid): its stencil, closed-form eigenvalues and the peers'
// own FFTW eigen coordinates agree with a dense eigendecomposition; the splitting peers on a
// grid agree with the runtime's ERKN path to the tolerance both reach.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>

#include "eigen_coordinates.hpp"
#include "grid_problems.hpp"
#include "splitting.hpp"

namespace ex {
namespace {

using B = GridAxis::Boundary;

std::vector<LinearPart> grids() {
  return {
      LinearPart::grid({{5, 0.3, B::periodic}, {4, 0.5, B::dirichlet}}, 1.0),
      LinearPart::grid({{3, 1.0, B::neumann}, {4, 0.4, B::periodic}, {2, 0.7, B::dirichlet}}, 0.0),
      LinearPart::grid({{6, 0.2, B::neumann}}, 0.5)};
}

TEST(GridPeers, StencilEigenvaluesAndEigenCoordinatesMatchTheDenseMatrix) {
  for (const LinearPart& M : grids()) {
    int d = 1;
    for (const GridAxis& a : M.axes) d *= a.n;
    const Eigen::MatrixXd dense = M.dense(d);
    ASSERT_LE((dense - dense.transpose()).cwiseAbs().maxCoeff(), 1e-12);
    Vec closed = M.eigenvalues(d);
    Vec exact = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues();
    std::sort(closed.begin(), closed.end());
    EXPECT_LE((closed - exact).cwiseAbs().maxCoeff(), 1e-12 * exact.cwiseAbs().maxCoeff());
#ifdef EX_WITH_FFTW
    EigenCoordinates basis(M, d);
    const Vec x = Vec::LinSpaced(d, -1, 2).array().sin();
    Vec y, back, Mx_spectral;
    basis.to(x, y);
    basis.from(y, back);
    EXPECT_LE((back - x).cwiseAbs().maxCoeff(), 1e-13);
    basis.from((basis.lambda().array() * y.array()).matrix(), Mx_spectral);
    const Vec Mx = dense * x;
    EXPECT_LE((Mx_spectral - Mx).cwiseAbs().maxCoeff(), 1e-12 * Mx.cwiseAbs().maxCoeff());
    // Negative control: the eigenvalues reversed do not diagonalise M.
    basis.from((basis.lambda().reverse().array() * y.array()).matrix(), Mx_spectral);
    EXPECT_GE((Mx_spectral - Mx).cwiseAbs().maxCoeff(), 1e-6);
#endif
  }
}

#ifdef EX_WITH_FFTW
TEST(GridPeers, SplittingPeersConvergeOnTheGridScenesAtLeastAtTheirOrder) {
  for (const Problem& p : {sine_gordon_2d(16), klein_gordon_3d(6)}) {
    const auto s = make_splitting(blanes_moan_srkn6b());
    const Vec ref = s->run(p, 1.0 / 256, 256, nullptr).q;
    const double e1 = (s->run(p, 1.0 / 16, 16, nullptr).q - ref).lpNorm<Eigen::Infinity>();
    const double e2 = (s->run(p, 1.0 / 32, 32, nullptr).q - ref).lpNorm<Eigen::Infinity>();
    SCOPED_TRACE(p.title);
    EXPECT_GE(std::log2(e1 / e2), 3.6);  // at least order 4 (pre-asymptotically more)
  }
}
#endif

}  // namespace
}  // namespace ex
