// The transform into M's eigenbasis for an M distributed over MPI ranks: the one dependency of
// the slab space (slab_space.hpp) on the form of M. A rank owns a contiguous part of the
// unknowns (rows first_row() .. of axis 0 of a grid, entries first_row() .. of a circulant
// vector; physical_size() unknowns) and a part of the eigen coordinates (spectral_size(), each
// with its eigenvalue of M and its norm weight: |x|^2 = the sum over every rank of W y^2).
// Implementations: PeriodicSlabTransform (grids of two or more axes, all periodic:
// periodic_slab_transform.hpp), SlabTransform (other grids of two or more axes,
// slab_transform.hpp) and CirculantTransform (circulant M, circulant_transform.hpp); a new form
// of M is one more.
#pragma once

#include <mpi.h>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "erkn/stiffness.hpp"

namespace erkn::mpi::detail {

/// The unknowns a rank owns: entries first .. first + size - 1 of the vector in row-major order,
/// `rows` rows of axis 0 (rows = size for a vector).
struct LocalPart {
  Eigen::Index first = 0, rows = 0, size = 0;
};

class DistributedTransform {
 public:
  virtual ~DistributedTransform() = default;

  Eigen::Index physical_size() const { return part_.size; }
  Eigen::Index spectral_size() const { return lambda_.size(); }
  Eigen::Index first_row() const { return part_.first; }  ///< first local index along axis 0
  Eigen::Index rows() const { return part_.rows; }        ///< local extent along axis 0
  /// Eigenvalue of M and norm weight of each local spectral coordinate.
  const Eigen::ArrayXd& eigenvalues() const { return lambda_; }
  const Eigen::ArrayXd& weights() const { return weights_; }
  /// The index in M.eigenvalues() of local spectral coordinate `local` (where its eigenvalue is).
  virtual Eigen::Index mode(Eigen::Index local) const = 0;
  /// Collective: y = forward(x), x = inverse(y) (normalised so inverse(forward(x)) = x).
  void forward(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::ArrayXd> y) {
    const double start = MPI_Wtime();
    execute_forward(x, y);
    ++count_, seconds_ += MPI_Wtime() - start;
  }
  void inverse(const Eigen::Ref<const Eigen::ArrayXd>& y, Eigen::Ref<Eigen::VectorXd> x) {
    Eigen::Map<Eigen::ArrayXd>(staging_, spectral_size()) = scale_ * y;
    inverse_staged(x);
  }
  /// The inverse transform's input buffer (spectral_size() coordinates in the order of y) and
  /// the factor y is written there with (the normalisation): the explicit stepper's flow writes
  /// the stage's eigen coordinates there as it computes them, and inverse_staged transforms
  /// them with no copy pass (collective; the buffer's contents are lost).
  double* staging() { return staging_; }
  double staging_scale() const { return scale_; }
  void inverse_staged(Eigen::Ref<Eigen::VectorXd> x) {
    const double start = MPI_Wtime();
    execute_inverse_staged(x);
    ++count_, seconds_ += MPI_Wtime() - start;
  }
  /// Transforms executed by this rank (each one all-to-all over comm).
  long count() const { return count_; }
  /// Wall time spent in them (MPI_Wtime).
  double seconds() const { return seconds_; }

 protected:
  virtual void execute_forward(const Eigen::Ref<const Eigen::VectorXd>& x,
                               Eigen::Ref<Eigen::ArrayXd> y) = 0;
  virtual void execute_inverse_staged(Eigen::Ref<Eigen::VectorXd> x) = 0;

  LocalPart part_;
  Eigen::ArrayXd lambda_, weights_;
  double* staging_ = nullptr;  // (an implementation's buffer)
  double scale_ = 1;           // 1 / the product of FFTW's logical sizes

 private:
  long count_ = 0;
  double seconds_ = 0;
};

/// The part of M's unknowns this rank owns (collective; erkn::Error on every rank unless M is a
/// grid with at least two axes or circulant).
LocalPart local_part(MPI_Comm comm, const Stiffness& M);

/// The transform for M (collective; the same errors as local_part).
std::unique_ptr<DistributedTransform> distributed_transform(MPI_Comm comm, const Stiffness& M);

/// The outer sum (product = false: eigenvalues) or product (weights) of per-axis factors,
/// row-major.
Eigen::ArrayXd outer(const std::vector<Eigen::ArrayXd>& factors, bool product);

/// fftw_mpi_init, once per process.
void init_fftw_mpi();

}  // namespace erkn::mpi::detail
