#include "circulant_transform.hpp"

#include <algorithm>
#include <string>

#include "erkn/error.hpp"

namespace erkn::mpi::detail {
namespace {

CirculantLayout layout(MPI_Comm comm, ptrdiff_t n, int sign) {
  CirculantLayout l;
  l.buffer = fftw_mpi_local_size_1d(n, comm, sign, FFTW_ESTIMATE, &l.count_in, &l.first_in,
                                    &l.count_out, &l.first_out);
  return l;
}

}  // namespace

// The inverse DFT must read the forward's output distribution and write its input distribution.
CirculantLayout circulant_layout(MPI_Comm comm, ptrdiff_t n) {
  init_fftw_mpi();
  const CirculantLayout f = layout(comm, n, FFTW_FORWARD), b = layout(comm, n, FFTW_BACKWARD);
  if (b.count_in != f.count_out || b.first_in != f.first_out || b.count_out != f.count_in ||
      b.first_out != f.first_in)
    throw Error("FFTW-MPI distributes the inverse DFT of size " + std::to_string(n) +
                " differently from the forward one: use erkn::Integrator on one process");
  CirculantLayout l = f;
  l.buffer = std::max<ptrdiff_t>({f.buffer, b.buffer, 1});
  return l;
}

CirculantTransform::CirculantTransform(MPI_Comm comm, const Stiffness& M) {
  const ptrdiff_t n = ptrdiff_t(M.dim());
  const CirculantLayout l = circulant_layout(comm, n);
  part_ = {Eigen::Index(l.first_in), Eigen::Index(l.count_in), Eigen::Index(l.count_in)};
  scale_ = 1.0 / double(n);
  first_k_ = Eigen::Index(l.first_out), n_ = Eigen::Index(n);
  fftw_.in = fftw_alloc_complex(size_t(l.buffer));
  fftw_.out = fftw_alloc_complex(size_t(l.buffer));
  staging_ = &fftw_.in[0][0];  // (the inverse's input: (re, im) pairs, as the coordinates)
  fftw_.forward = fftw_mpi_plan_dft_1d(n, fftw_.in, fftw_.out, comm, FFTW_FORWARD, FFTW_ESTIMATE);
  fftw_.inverse = fftw_mpi_plan_dft_1d(n, fftw_.in, fftw_.out, comm, FFTW_BACKWARD, FFTW_ESTIMATE);
  if (!fftw_.forward || !fftw_.inverse)
    throw Error("FFTW-MPI cannot plan a distributed DFT of size " + std::to_string(n) +
                " on this many ranks (its 1-D transforms need n to factor over the ranks): use "
                "another size or erkn::Integrator on one process");
  const Eigen::VectorXd& half = M.eigenvalues();  // lambda_0 .. lambda_{n/2}
  lambda_.resize(2 * l.count_out);
  for (ptrdiff_t j = 0; j < l.count_out; ++j) {
    const ptrdiff_t k = l.first_out + j;
    lambda_[2 * j] = lambda_[2 * j + 1] = half[std::min(k, n - k)];
  }
  weights_ = Eigen::ArrayXd::Constant(lambda_.size(), scale_);
}

Eigen::Index CirculantTransform::mode(Eigen::Index local) const {
  const Eigen::Index k = first_k_ + local / 2;
  return std::min(k, n_ - k);
}

void CirculantTransform::execute_forward(const Eigen::Ref<const Eigen::VectorXd>& x,
                                         Eigen::Ref<Eigen::ArrayXd> y) {
  for (Eigen::Index j = 0; j < physical_size(); ++j) fftw_.in[j][0] = x[j], fftw_.in[j][1] = 0;
  fftw_execute(fftw_.forward);
  y = Eigen::Map<const Eigen::ArrayXd>(&fftw_.out[0][0], spectral_size());
}

void CirculantTransform::execute_inverse_staged(Eigen::Ref<Eigen::VectorXd> x) {
  fftw_execute(fftw_.inverse);
  for (Eigen::Index j = 0; j < physical_size(); ++j) x[j] = fftw_.out[j][0];
}

}  // namespace erkn::mpi::detail
