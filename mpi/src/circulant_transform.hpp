// The eigenbasis of a circulant M (Stiffness::circulant, a 1-D periodic stencil or spectral
// operator) distributed over MPI ranks: FFTW-MPI's 1-D complex DFT, in place of the single-process
// halfcomplex one. A rank owns entries first .. of the real vector (FFTW's local_ni) and the
// complex coefficients X_k, k in [first_k, first_k + count) (local_no), stored as (Re, Im) pairs
// of doubles. Both doubles of X_k carry lambda_k = lambda_{N-k} (M's eigenvalue of frequency k)
// and the weight 1/N (Parseval: |x|^2 = sum_k |X_k|^2 / N for the unnormalised forward DFT). The
// coefficients of a real vector satisfy X_{N-k} = conj(X_k); the step acts on each X_k through
// real functions of lambda_k, so they keep that symmetry, and inverse takes the real part.
#pragma once

#include <fftw3-mpi.h>

#include "distributed_transform.hpp"
#include "fftw_plans.hpp"

namespace erkn::mpi::detail {

/// FFTW-MPI's distribution of a 1-D DFT of size n: inputs first_in.., outputs first_out...
struct CirculantLayout {
  ptrdiff_t count_in = 0, first_in = 0, count_out = 0, first_out = 0, buffer = 0;
};
CirculantLayout circulant_layout(MPI_Comm comm, ptrdiff_t n);

class CirculantTransform final : public DistributedTransform {
 public:
  /// M must be circulant (collective over comm; throws erkn::Error on every rank when FFTW-MPI
  /// cannot plan the size on this many ranks).
  CirculantTransform(MPI_Comm comm, const Stiffness& M);
  /// Both doubles of X_k are at wave number min(k, N - k) of M.eigenvalues().
  Eigen::Index mode(Eigen::Index local) const override;

 private:
  void execute_forward(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::Ref<Eigen::ArrayXd> y) override;
  void execute_inverse_staged(Eigen::Ref<Eigen::VectorXd> x) override;

  FftwPlans<fftw_complex> fftw_;
  Eigen::Index first_k_ = 0, n_ = 0;  // (mode: the first local k, N)
};

}  // namespace erkn::mpi::detail
