#include "eigen_coordinates.hpp"

namespace ex {
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
  if (!fourier_) {
    y = x;
    return;
  }
  y.resize(lambda_.size());
  fft_.fwd(as_complex(y), x.data(), dim_);
}

void EigenCoordinates::from(const Vec& y, Vec& x) {
  if (!fourier_) {
    x = y;
    return;
  }
  x.resize(dim_);
  fft_.inv(x.data(), as_complex(y), dim_);
}

}  // namespace ex
