// The transforms into M's eigenbasis for a tensor grid distributed in slabs, with FFTW-MPI (grids
// with a Dirichlet or Neumann axis; all-periodic grids take periodic_slab_transform.hpp's faster
// real-to-complex DFT).
//
// Per axis the real transform of erkn::GridAxis (periodic: R2HC / HC2R; Dirichlet: RODFT00 both
// ways; Neumann: REDFT10 / REDFT01). The forward transform ends transposed
// (FFTW_MPI_TRANSPOSED_OUT: physical slab rows of axis 0 in, spectral rows of axis 1 out, each of
// the two axes whole in the other's layout) and the inverse starts from that layout
// (FFTW_MPI_TRANSPOSED_IN), so each costs exactly one all-to-all and the spectral data never needs
// transposing back. In spectral coordinates the local entry (k1 - first1, k0, k2, ..., k_{K-1})
// (row-major) has the eigenvalue shift + mu_0[k0] + mu_1[k1] + ... and the norm weight W_0[k0]
// W_1[k1] ... with |x|^2 = sum W y^2 (Parseval for the unnormalised forward transform).
#pragma once

#include <fftw3-mpi.h>
#include <mpi.h>

#include <Eigen/Core>
#include <vector>

#include "distributed_transform.hpp"
#include "erkn/stiffness.hpp"
#include "fftw_plans.hpp"

namespace erkn::mpi::detail {

/// FFTW-MPI's distribution of a grid: physical rows first0.. of axis 0, spectral rows first1.. of
/// axis 1, and the local buffer size including room for the transposes.
struct SlabLayout {
  std::vector<ptrdiff_t> n;  // the axes' sizes
  ptrdiff_t rows0 = 0, first0 = 0, rows1 = 0, first1 = 0, buffer = 0;
  Eigen::Index physical_size = 0, spectral_size = 0;
};

/// The layout of M over comm (collective; erkn::Error on every rank unless M is a grid with at
/// least two axes).
SlabLayout slab_layout(MPI_Comm comm, const Stiffness& M);

class SlabTransform final : public DistributedTransform {
 public:
  /// M must be a grid with at least two axes (collective over comm; throws erkn::Error on every
  /// rank otherwise).
  SlabTransform(MPI_Comm comm, const Stiffness& M);
  /// The local entry (k1 - first1, k0, k2, ...) is entry (k0, k1, k2, ...) of M.eigenvalues().
  Eigen::Index mode(Eigen::Index local) const override;

 private:
  void execute_forward(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::Ref<Eigen::ArrayXd> y) override;
  void execute_inverse_staged(Eigen::Ref<Eigen::VectorXd> x) override;

  FftwPlans<double> fftw_;
  Eigen::Index first1_ = 0, n0_ = 0, n1_ = 0, rest_ = 1;  // (mode: k1's offset, axis sizes)
};

}  // namespace erkn::mpi::detail
