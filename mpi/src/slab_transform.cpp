#include "slab_transform.hpp"

#include <string>

#include "erkn/error.hpp"
#include "grid_backend.hpp"  // (runtime/src: axis_weights)

namespace erkn::mpi::detail {
namespace {

using Boundary = GridAxis::Boundary;

struct AxisKind {
  fftw_r2r_kind forward, inverse;
  double logical_size;  // FFTW's N: inverse(forward(x)) = N x
};

// The kinds of runtime/src/fftw_backend.cpp (the single-process grid transform).
AxisKind kind_of(const GridAxis& a) {
  const double n = double(a.n);
  switch (a.boundary) {
    case Boundary::periodic:
      return {FFTW_R2HC, FFTW_HC2R, n};
    case Boundary::dirichlet:
      return {FFTW_RODFT00, FFTW_RODFT00, 2 * (n + 1)};
    case Boundary::neumann:
      return {FFTW_REDFT10, FFTW_REDFT01, 2 * n};
  }
  throw Error("unknown grid boundary");
}

}  // namespace

SlabLayout slab_layout(MPI_Comm comm, const Stiffness& M) {
  if (M.structure() != Stiffness::Structure::grid || M.axes().size() < 2)
    throw Error(
        "the distributed integrator needs M = Stiffness::grid with at least two axes (FFTW-MPI "
        "distributes slabs of axis 0) or Stiffness::circulant; use erkn::Integrator for other "
        "forms of M");
  init_fftw_mpi();
  SlabLayout l;
  ptrdiff_t rest = 1;  // prod of n_2.. n_{K-1}
  for (std::size_t a = 0; a < M.axes().size(); ++a) {
    l.n.push_back(ptrdiff_t(M.axes()[a].n));
    if (a >= 2) rest *= l.n[a];
  }
  l.buffer = fftw_mpi_local_size_many_transposed(int(l.n.size()), l.n.data(), 1,
                                                 FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK,
                                                 comm, &l.rows0, &l.first0, &l.rows1, &l.first1);
  l.physical_size = l.rows0 * l.n[1] * rest;
  l.spectral_size = l.rows1 * l.n[0] * rest;
  return l;
}

SlabTransform::SlabTransform(MPI_Comm comm, const Stiffness& M) {
  SlabLayout l = slab_layout(comm, M);
  const std::vector<GridAxis>& axes = M.axes();
  std::vector<fftw_r2r_kind> forward_kinds, inverse_kinds;
  for (const GridAxis& axis : axes) {
    const AxisKind k = kind_of(axis);
    forward_kinds.push_back(k.forward), inverse_kinds.push_back(k.inverse);
    scale_ /= k.logical_size;
  }
  part_ = {Eigen::Index(l.first0), Eigen::Index(l.rows0), l.physical_size};
  first1_ = l.first1, n0_ = l.n[0], n1_ = l.n[1], rest_ = M.dim() / (n0_ * n1_);
  fftw_.in = fftw_alloc_real(std::max<ptrdiff_t>(l.buffer, 1));
  fftw_.out = fftw_alloc_real(std::max<ptrdiff_t>(l.buffer, 1));
  const int rank = int(axes.size());
  fftw_.forward = fftw_mpi_plan_r2r(rank, l.n.data(), fftw_.in, fftw_.out, comm,
                                    forward_kinds.data(), FFTW_ESTIMATE | FFTW_MPI_TRANSPOSED_OUT);
  fftw_.inverse = fftw_mpi_plan_r2r(rank, l.n.data(), fftw_.in, fftw_.out, comm,
                                    inverse_kinds.data(), FFTW_ESTIMATE | FFTW_MPI_TRANSPOSED_IN);
  if (!fftw_.forward || !fftw_.inverse) throw Error("FFTW-MPI could not plan the grid transforms");
  staging_ = fftw_.in;  // (the inverse's input)
  // Spectral layout: (k1 local, k0, k2, ...).
  std::vector<Eigen::ArrayXd> mu, w;
  const auto add = [&](const GridAxis& a, Eigen::Index first, Eigen::Index count) {
    mu.push_back(a.eigenvalues().array().segment(first, count));
    w.push_back(erkn::detail::axis_weights(a).segment(first, count));
  };
  add(axes[1], l.first1, l.rows1);
  add(axes[0], 0, axes[0].n);
  for (std::size_t a = 2; a < axes.size(); ++a) add(axes[a], 0, axes[a].n);
  lambda_ = (outer(mu, false) + M.shift()).max(0.0);  // (round-off negatives, as M.eigenvalues())
  weights_ = outer(w, true);
}

Eigen::Index SlabTransform::mode(Eigen::Index local) const {
  const Eigen::Index r = local % rest_, k0 = (local / rest_) % n0_,
                     k1 = first1_ + local / (rest_ * n0_);
  return (k0 * n1_ + k1) * rest_ + r;
}

void SlabTransform::execute_forward(const Eigen::Ref<const Eigen::VectorXd>& x,
                                    Eigen::Ref<Eigen::ArrayXd> y) {
  Eigen::Map<Eigen::VectorXd>(fftw_.in, physical_size()) = x;
  fftw_execute(fftw_.forward);
  y = Eigen::Map<const Eigen::ArrayXd>(fftw_.out, spectral_size());
}

void SlabTransform::execute_inverse_staged(Eigen::Ref<Eigen::VectorXd> x) {
  fftw_execute(fftw_.inverse);
  x = Eigen::Map<const Eigen::VectorXd>(fftw_.out, physical_size());
}

}  // namespace erkn::mpi::detail
