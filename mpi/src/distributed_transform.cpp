#include "distributed_transform.hpp"

#include <fftw3-mpi.h>

#include <mutex>

#include "circulant_transform.hpp"
#include "erkn/error.hpp"
#include "periodic_slab_transform.hpp"
#include "slab_transform.hpp"

namespace erkn::mpi::detail {
namespace {

bool circulant(const Stiffness& M) { return M.structure() == Stiffness::Structure::circulant; }

}  // namespace

Eigen::ArrayXd outer(const std::vector<Eigen::ArrayXd>& factors, bool product) {
  Eigen::ArrayXd acc = Eigen::ArrayXd::Constant(1, product ? 1.0 : 0.0);
  for (const Eigen::ArrayXd& f : factors) {
    Eigen::ArrayXd next(acc.size() * f.size());
    for (Eigen::Index i = 0; i < acc.size(); ++i)
      next.segment(i * f.size(), f.size()) = product ? (acc[i] * f).eval() : (acc[i] + f).eval();
    acc.swap(next);
  }
  return acc;
}

void init_fftw_mpi() {
  static std::once_flag once;
  std::call_once(once, [] { fftw_mpi_init(); });
}

LocalPart local_part(MPI_Comm comm, const Stiffness& M) {
  if (circulant(M)) {
    const CirculantLayout l = circulant_layout(comm, ptrdiff_t(M.dim()));
    return {Eigen::Index(l.first_in), Eigen::Index(l.count_in), Eigen::Index(l.count_in)};
  }
  if (all_periodic(M)) {
    const PeriodicSlabLayout l = periodic_slab_layout(comm, M);
    return {Eigen::Index(l.first0), Eigen::Index(l.rows0), l.physical_size};
  }
  const SlabLayout l = slab_layout(comm, M);  // (refuses other forms of M)
  return {Eigen::Index(l.first0), Eigen::Index(l.rows0), l.physical_size};
}

std::unique_ptr<DistributedTransform> distributed_transform(MPI_Comm comm, const Stiffness& M) {
  if (circulant(M)) return std::make_unique<CirculantTransform>(comm, M);
  if (all_periodic(M)) return std::make_unique<PeriodicSlabTransform>(comm, M);
  return std::make_unique<SlabTransform>(comm, M);
}

}  // namespace erkn::mpi::detail
