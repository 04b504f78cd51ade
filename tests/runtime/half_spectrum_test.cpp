// The complex half spectrum of periodic grids and circulant M (HalfSpectrumTransform, FFTW's
// r2c/c2r or Eigen's real FFT): against the DFT's definition, Parseval with the coordinates that
// stand for two (X_k and X_{-k}) counted twice, and M diagonalised by half_spectrum_eigenvalues.
// Negative controls: self-conjugate coordinates (k = 0, Nyquist) weighted like the others break
// Parseval; eigenvalues in another order do not diagonalise M. Arrays transformed in turn (the
// transforms are bound to their arrays) each get their own transform.
#include <gtest/gtest.h>

#include <complex>
#include <numbers>

#include "problems.hpp"
#include "transforms.hpp"

namespace erkn::test {
namespace {

using B = GridAxis::Boundary;

// All-periodic grids: one to three axes, odd and even n (n = 1 and 2 too), the odd axis last
// and not last.
std::vector<std::vector<GridAxis>> periodic_grids() {
  std::vector<std::vector<GridAxis>> out;
  for (Eigen::Index n : {1, 2, 4, 5, 8, 9}) out.push_back({{n, 0.3, B::periodic}});
  out.push_back({{4, 0.5, B::periodic}, {5, 0.25, B::periodic}});
  out.push_back({{5, 0.5, B::periodic}, {4, 0.25, B::periodic}});
  out.push_back({{3, 1.0, B::periodic}, {4, 0.5, B::periodic}, {2, 2.0, B::periodic}});
  out.push_back({{2, 0.7, B::periodic}, {3, 0.4, B::periodic}, {5, 0.2, B::periodic}});
  return out;
}

std::string describe(const std::vector<GridAxis>& axes) {
  std::string s;
  for (const GridAxis& a : axes) s += std::to_string(a.n) + (&a == &axes.back() ? "" : " x ");
  return s;
}

// X_k = sum_j x_j exp(-2 pi i sum_a k_a j_a / n_a) at the half spectrum's k (row-major, the last
// axis's k_a up to n/2), summed directly.
Eigen::VectorXcd dft_half_spectrum(const std::vector<GridAxis>& axes, const Eigen::VectorXd& x) {
  const Eigen::Index m = detail::half_spectrum_size(axes), K = Eigen::Index(axes.size());
  Eigen::VectorXcd X = Eigen::VectorXcd::Zero(m);
  for (Eigen::Index c = 0; c < m; ++c)
    for (Eigen::Index j = 0; j < x.size(); ++j) {
      Eigen::Index rc = c, rj = j;
      double phase = 0;  // (in turns)
      for (Eigen::Index a = K - 1; a >= 0; --a) {
        const Eigen::Index n = axes[a].n, nk = a == K - 1 ? n / 2 + 1 : n;
        phase += double((rc % nk) * (rj % n) % n) / double(n);
        rc /= nk, rj /= n;
      }
      X[c] += x[j] * std::polar(1.0, -2 * std::numbers::pi * phase);
    }
  return X;
}

TEST(HalfSpectrum, ForwardIsTheDftAndInverseUndoesIt) {
  int checked = 0;
  for (const auto& axes : periodic_grids()) {
    if (!detail::half_spectrum_available(axes)) continue;
    SCOPED_TRACE(describe(axes));
    ++checked;
    detail::HalfSpectrumTransform t(axes);
    const Eigen::VectorXd x = random_vector(Stiffness::grid(axes).dim(), 3);
    Eigen::VectorXd x_in = x, back(x.size());
    Eigen::ArrayXcd y(t.spectral_size(x.size()));
    t.forward(x_in, y);
    EXPECT_EQ(x_in, x) << "forward changed its input";
    const Eigen::VectorXcd X = dft_half_spectrum(axes, x);
    EXPECT_LE((y.matrix() - X).cwiseAbs().maxCoeff(), 1e-13 * x.cwiseAbs().sum());
    const Eigen::ArrayXcd y_in = y;
    t.inverse(y_in, back);
    EXPECT_TRUE((y_in == y).all()) << "inverse changed its input";
    EXPECT_LE((back - x).cwiseAbs().maxCoeff(), 1e-14 * x.cwiseAbs().maxCoeff());
  }
  EXPECT_GE(checked, 4);  // (without FFTW: the one-axis grids of n >= 4)
}

TEST(HalfSpectrum, NormIsParsevalsAndMisweightedSelfConjugateCoordinatesBreakIt) {
  for (const auto& axes : periodic_grids()) {
    if (!detail::half_spectrum_available(axes)) continue;
    SCOPED_TRACE(describe(axes));
    detail::HalfSpectrumTransform t(axes);
    const Eigen::VectorXd x = random_vector(Stiffness::grid(axes).dim(), 4);
    Eigen::ArrayXcd y(t.spectral_size(x.size()));
    t.forward(x, y);
    EXPECT_NEAR(std::sqrt(t.squared_norm(y)), x.norm(), 1e-14 * x.norm());
    // Negative control: k_last = 0 (and n/2) weighted 2/d like the rest, as if each stood for
    // two coordinates.
    const Eigen::ArrayXd misweighted = Eigen::ArrayXd::Constant(y.size(), t.weight().maxCoeff());
    const double wrong = std::sqrt((misweighted * y.abs2()).sum());
    if (y.size() > 1 && t.weight().minCoeff() < t.weight().maxCoeff())
      EXPECT_GE(std::abs(wrong - x.norm()), 1e-3 * x.norm());
  }
}

TEST(HalfSpectrum, EigenvaluesDiagonaliseMAndAnotherOrderDoesNot) {
  for (const auto& axes : periodic_grids()) {
    if (!detail::half_spectrum_available(axes)) continue;
    SCOPED_TRACE(describe(axes));
    const Stiffness M = Stiffness::grid(axes, 0.5);
    const Eigen::Index d = M.dim();
    detail::HalfSpectrumTransform t(axes);
    const Eigen::VectorXd x = random_vector(d, 5), Mx = M.to_dense(d) * x;
    const Eigen::ArrayXd lambda = detail::half_spectrum_eigenvalues(axes, M.shift()).array();
    Eigen::ArrayXcd y(t.spectral_size(d)), ly(y.size());
    Eigen::VectorXd back(d);
    t.forward(x, y);
    ly = lambda * y;
    t.inverse(ly, back);
    EXPECT_LE((back - Mx).cwiseAbs().maxCoeff(), 1e-12 * Mx.cwiseAbs().maxCoeff());
    if (lambda.maxCoeff() - lambda.minCoeff() < 1e-9 || lambda.isApprox(lambda.reverse())) continue;
    ly = lambda.reverse() * y;
    t.inverse(ly, back);
    EXPECT_GE((back - Mx).cwiseAbs().maxCoeff(), 1e-6 * Mx.cwiseAbs().maxCoeff());
  }
}

// The transforms are bound to the arrays they last saw (the last three pairs): arrays taken in
// turn, one of them off FFTW's planned alignment (one double into a buffer), two inputs into one
// output, must each get their own transform, as must staged inverses into outputs in turn (a cache
// keyed on the input or on the output alone fails here). Negative control: the inputs' DFTs differ
// by far more than the tolerance, so an output from another array's binding would show.
TEST(HalfSpectrum, ArraysTransformedInTurnEachGetTheirOwnTransform) {
  for (const auto& axes : periodic_grids()) {
    if (!detail::half_spectrum_available(axes)) continue;
    SCOPED_TRACE(describe(axes));
    detail::HalfSpectrumTransform t(axes);
    const Eigen::Index d = Stiffness::grid(axes).dim(), m = t.spectral_size(d);
    std::vector<Eigen::VectorXd> x;
    std::vector<Eigen::VectorXcd> X;
    for (int k = 0; k < 3; ++k) {
      x.push_back(random_vector(d, 10 + k));
      X.push_back(dft_half_spectrum(axes, x.back()));
    }
    for (int k = 0; k < 3; ++k) EXPECT_GT((X[k] - X[(k + 1) % 3]).cwiseAbs().maxCoeff(), 1e-3);
    Eigen::VectorXd shifted_x(d + 1), shifted_back(d + 1);  // (the arrays at one double in)
    Eigen::VectorXcd shifted_y(m + 1);
    shifted_x.tail(d) = x[2];
    std::vector<Eigen::ArrayXcd> y(3, Eigen::ArrayXcd(m));
    Eigen::ArrayXcd shared(m);
    std::vector<Eigen::VectorXd> back(3, Eigen::VectorXd(d));
    for (int round = 0; round < 3; ++round)
      for (int k = 0; k < 3; ++k) {
        if (k < 2)
          t.forward(x[k], y[k]);
        else
          t.forward(shifted_x.tail(d), shifted_y.tail(m)), y[k] = shifted_y.tail(m);
        EXPECT_LE((y[k].matrix() - X[k]).cwiseAbs().maxCoeff(), 1e-13 * x[k].cwiseAbs().sum());
        t.forward(x[k % 2], shared);  // (two inputs in turn into one output)
        EXPECT_LE((shared.matrix() - X[k % 2]).cwiseAbs().maxCoeff(),
                  1e-13 * x[k % 2].cwiseAbs().sum());
        Eigen::Map<Eigen::ArrayXcd>(reinterpret_cast<std::complex<double>*>(t.staging()), m) =
            t.staging_scale() * y[k];
        if (k < 2)
          t.inverse_staged(back[k]);
        else
          t.inverse_staged(shifted_back.tail(d)), back[k] = shifted_back.tail(d);
        EXPECT_LE((back[k] - x[k]).cwiseAbs().maxCoeff(), 1e-14 * x[k].cwiseAbs().maxCoeff());
      }
  }
}
}  // namespace
}  // namespace erkn::test
