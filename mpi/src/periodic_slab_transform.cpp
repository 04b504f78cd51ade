#include "periodic_slab_transform.hpp"

#include "erkn/error.hpp"
#include "grid_backend.hpp"  // (runtime/src: axis_weights)

namespace erkn::mpi::detail {
namespace {

// outer() with each entry twice (the real and imaginary parts of a complex entry).
Eigen::ArrayXd outer_pairs(const std::vector<Eigen::ArrayXd>& factors, bool product) {
  const Eigen::ArrayXd acc = outer(factors, product);
  Eigen::ArrayXd pairs(2 * acc.size());
  for (Eigen::Index i = 0; i < acc.size(); ++i) pairs[2 * i] = pairs[2 * i + 1] = acc[i];
  return pairs;
}

}  // namespace

bool all_periodic(const Stiffness& M) {
  if (M.structure() != Stiffness::Structure::grid || M.axes().size() < 2) return false;
  for (const GridAxis& a : M.axes())
    if (a.boundary != GridAxis::Boundary::periodic) return false;
  return true;
}

PeriodicSlabLayout periodic_slab_layout(MPI_Comm comm, const Stiffness& M) {
  init_fftw_mpi();
  PeriodicSlabLayout l;
  for (const GridAxis& a : M.axes()) l.n.push_back(ptrdiff_t(a.n));
  l.nc = l.n;
  l.nc.back() = l.n.back() / 2 + 1;
  l.buffer = fftw_mpi_local_size_many_transposed(int(l.nc.size()), l.nc.data(), 1,
                                                 FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK,
                                                 comm, &l.rows0, &l.first0, &l.rows1, &l.first1);
  Eigen::Index physical = l.rows0, complex = l.rows1 * l.nc[0];
  for (std::size_t a = 1; a < l.n.size(); ++a) physical *= l.n[a];
  for (std::size_t a = 2; a < l.n.size(); ++a) complex *= l.nc[a];
  l.physical_size = physical, l.spectral_size = 2 * complex;
  return l;
}

PeriodicSlabTransform::PeriodicSlabTransform(MPI_Comm comm, const Stiffness& M)
    : layout_(periodic_slab_layout(comm, M)) {
  const PeriodicSlabLayout& l = layout_;
  part_ = {Eigen::Index(l.first0), Eigen::Index(l.rows0), l.physical_size};
  scale_ = 1.0 / double(M.dim());
  fftw_.in = fftw_alloc_real(2 * std::max<ptrdiff_t>(l.buffer, 1));
  fftw_.out = fftw_alloc_real(2 * std::max<ptrdiff_t>(l.buffer, 1));
  auto* spectrum = reinterpret_cast<fftw_complex*>(fftw_.out);
  const int rank = int(l.n.size());
  fftw_.forward =
      fftw_mpi_plan_dft_r2c(rank, l.n.data(), fftw_.in, spectrum, comm,
                            FFTW_MEASURE | FFTW_MPI_TRANSPOSED_OUT | FFTW_DESTROY_INPUT);
  fftw_.inverse = fftw_mpi_plan_dft_c2r(rank, l.n.data(), spectrum, fftw_.in, comm,
                                        FFTW_MEASURE | FFTW_MPI_TRANSPOSED_IN);
  if (!fftw_.forward || !fftw_.inverse) throw Error("FFTW-MPI could not plan the grid transforms");
  staging_ = fftw_.out;  // (the spectrum c2r reads)
  // Spectral layout: (k1 local, k0, k2, .., k_{K-1} halved), two coordinates per entry.
  const std::vector<GridAxis>& axes = M.axes();
  const std::size_t last = axes.size() - 1;
  std::vector<Eigen::ArrayXd> mu, w;
  const auto add = [&](std::size_t a, Eigen::Index first, Eigen::Index count) {
    mu.push_back(axes[a].eigenvalues().array().segment(first, count));
    w.push_back(a == last ? erkn::detail::axis_weights(axes[a]).segment(first, count).eval()
                          : Eigen::ArrayXd::Constant(count, 1.0 / double(axes[a].n)));
  };
  add(1, l.first1, l.rows1);
  add(0, 0, l.nc[0]);
  for (std::size_t a = 2; a < axes.size(); ++a) add(a, 0, l.nc[a]);
  lambda_ = (outer_pairs(mu, false) + M.shift()).max(0.0);  // (as M.eigenvalues())
  weights_ = outer_pairs(w, true);
}

Eigen::Index PeriodicSlabTransform::mode(Eigen::Index local) const {
  const std::vector<ptrdiff_t>&n = layout_.n, &nc = layout_.nc;
  Eigen::Index rest = local / 2, index_tail = 0, tail_size = 1;  // (k2 .. k_{K-1})
  for (std::size_t a = n.size(); a-- > 2;) {
    index_tail += (rest % nc[a]) * tail_size;
    tail_size *= n[a], rest /= nc[a];
  }
  const Eigen::Index k0 = rest % nc[0], k1 = layout_.first1 + rest / nc[0];
  return (k0 * n[1] + k1) * tail_size + index_tail;
}

Eigen::Map<Eigen::ArrayXXd, 0, Eigen::OuterStride<>> PeriodicSlabTransform::padded() {
  const Eigen::Index n_last = layout_.n.back(), lines = layout_.physical_size / n_last;
  return {fftw_.in, n_last, lines, Eigen::OuterStride<>(2 * layout_.nc.back())};
}

void PeriodicSlabTransform::execute_forward(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            Eigen::Ref<Eigen::ArrayXd> y) {
  const Eigen::Index n_last = layout_.n.back();
  padded() = Eigen::Map<const Eigen::ArrayXXd>(x.data(), n_last, x.size() / n_last);
  // Straight into y when y is FFTW's whole local output (no transpose room beyond the spectrum:
  // one rank, for one) with the planned alignment: no copy pass.
  if (2 * layout_.buffer == y.size() &&
      fftw_alignment_of(y.data()) == fftw_alignment_of(fftw_.out)) {
    fftw_mpi_execute_dft_r2c(fftw_.forward, fftw_.in, reinterpret_cast<fftw_complex*>(y.data()));
    return;
  }
  fftw_execute(fftw_.forward);
  y = Eigen::Map<const Eigen::ArrayXd>(fftw_.out, spectral_size());
}

void PeriodicSlabTransform::execute_inverse_staged(Eigen::Ref<Eigen::VectorXd> x) {
  const Eigen::Index n_last = layout_.n.back();
  fftw_execute(fftw_.inverse);  // (c2r: destroys its input, the staged y)
  Eigen::Map<Eigen::ArrayXXd>(x.data(), n_last, x.size() / n_last) = padded();
}

}  // namespace erkn::mpi::detail
