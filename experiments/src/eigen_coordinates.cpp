#include "eigen_coordinates.hpp"

#include <stdexcept>
#ifdef EX_WITH_FFTW
#include <fftw3.h>
#endif

namespace ex {

#ifdef EX_WITH_FFTW
// Out-of-place r2r plans on private buffers, executed on copies (FFTW may overwrite its input).
struct EigenCoordinates::GridPlans {
  explicit GridPlans(const std::vector<GridAxis>& axes) {
    std::vector<int> n;
    std::vector<fftw_r2r_kind> fwd, inv;
    for (const GridAxis& a : axes) {
      n.push_back(a.n);
      switch (a.boundary) {
        case GridAxis::Boundary::periodic:
          fwd.push_back(FFTW_R2HC), inv.push_back(FFTW_HC2R), scale /= a.n;
          break;
        case GridAxis::Boundary::dirichlet:
          fwd.push_back(FFTW_RODFT00), inv.push_back(FFTW_RODFT00), scale /= 2.0 * (a.n + 1);
          break;
        case GridAxis::Boundary::neumann:
          fwd.push_back(FFTW_REDFT10), inv.push_back(FFTW_REDFT01), scale /= 2.0 * a.n;
          break;
      }
      size *= a.n;
    }
    in = fftw_alloc_real(size), out = fftw_alloc_real(size);
    forward = fftw_plan_r2r(int(n.size()), n.data(), in, out, fwd.data(), FFTW_ESTIMATE);
    inverse = fftw_plan_r2r(int(n.size()), n.data(), in, out, inv.data(), FFTW_ESTIMATE);
    if (!in || !out || !forward || !inverse) throw std::runtime_error("FFTW grid plan failed");
  }
  ~GridPlans() {
    if (forward) fftw_destroy_plan(forward);
    if (inverse) fftw_destroy_plan(inverse);
    fftw_free(in), fftw_free(out);
  }
  void run(fftw_plan plan, const Vec& x, Vec& y, double factor) {
    std::copy(x.data(), x.data() + size, in);
    fftw_execute_r2r(plan, in, out);
    y = factor * Eigen::Map<const Vec>(out, size);
  }
  std::size_t size = 1;
  double scale = 1;
  double *in = nullptr, *out = nullptr;
  fftw_plan forward = nullptr, inverse = nullptr;
};
#else
struct EigenCoordinates::GridPlans {
  explicit GridPlans(const std::vector<GridAxis>&) {
    throw std::runtime_error("a grid M needs FFTW in the experiments (libfftw3-dev)");
  }
  void run(int, const Vec&, Vec&, double) {}
  int forward = 0, inverse = 0;
  double scale = 1;
};
#endif

EigenCoordinates::~EigenCoordinates() = default;

namespace {

std::complex<double>* as_complex(Vec& v) {
  return reinterpret_cast<std::complex<double>*>(v.data());
}

const std::complex<double>* as_complex(const Vec& v) {
  return reinterpret_cast<const std::complex<double>*>(v.data());
}

}  // namespace

EigenCoordinates::EigenCoordinates(const LinearPart& m, int dim)
    : dim_(dim), fourier_(m.kind == LinearPart::Kind::circulant) {
  const Vec lambda = m.eigenvalues(dim);
  if (m.kind == LinearPart::Kind::grid) grid_ = std::make_unique<GridPlans>(m.axes);
  if (!fourier_) {
    lambda_ = lambda;
    return;
  }
  fft_.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  const int half = dim / 2 + 1;
  lambda_.resize(2 * half);
  for (int k = 0; k < half; ++k) lambda_[2 * k] = lambda_[2 * k + 1] = lambda[k];
}

void EigenCoordinates::to(const Vec& x, Vec& y) {
  if (grid_) return grid_->run(grid_->forward, x, y, 1.0);
  if (!fourier_) {
    y = x;
    return;
  }
  y.resize(lambda_.size());
  fft_.fwd(as_complex(y), x.data(), dim_);
}

void EigenCoordinates::from(const Vec& y, Vec& x) {
  if (grid_) return grid_->run(grid_->inverse, y, x, grid_->scale);
  if (!fourier_) {
    x = y;
    return;
  }
  x.resize(dim_);
  fft_.inv(x.data(), as_complex(y), dim_);
}

}  // namespace ex
