#include "slab_advice.hpp"

#include <array>
#include <limits>

#include "collective.hpp"
#include "erkn/error.hpp"

namespace erkn::mpi::detail {
namespace {

// Bounds on the Hessian of U at q. grad U is pointwise (erkn/mpi.hpp), so its Hessian is
// diagonal: one difference quotient per point from one more gradient, with hessian_bounds_at's
// steps 1e-6 max(1, |q_j|); the extremes over every rank.
HessianBounds diagonal_hessian_bounds(MPI_Comm comm, const System& system,
                                      const Eigen::VectorXd& q) {
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  std::array<double, 2> extremes{kNone, kNone};  // -lo, hi
  collectively(comm, [&] {
    if (q.size() == 0) return;
    const Eigen::ArrayXd step = 1e-6 * q.array().abs().max(1.0);
    const Eigen::VectorXd x = q + step.matrix();
    Eigen::VectorXd g0, g;
    system.gradient(q, g0);
    system.gradient(x, g);
    if (g0.size() != q.size() || g.size() != q.size() || !g0.allFinite() || !g.allFinite())
      throw Error("the gradient near the kept state is not finite or of the slab's size");
    const Eigen::ArrayXd kappa = (g - g0).array() / step;
    extremes = {-kappa.minCoeff(), kappa.maxCoeff()};
  });
  MPI_Allreduce(MPI_IN_PLACE, extremes.data(), 2, MPI_DOUBLE, MPI_MAX, comm);
  return {-extremes[0], extremes[1]};
}

// mode_energies (erkn/advisor.hpp) of the distributed state: 1/2 W (y_p^2 + lambda y_q^2) per
// local spectral coordinate, added at its eigenvalue's index (DistributedTransform::mode) and
// summed over every rank.
Eigen::VectorXd distributed_mode_energies(MPI_Comm comm, DistributedTransform& T,
                                          const Stiffness& M, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& p) {
  Eigen::ArrayXd yq(T.spectral_size()), yp(T.spectral_size());
  T.forward(q, yq);
  T.forward(p, yp);
  const Eigen::ArrayXd e = 0.5 * T.weights() * (yp.square() + T.eigenvalues() * yq.square());
  Eigen::VectorXd out = Eigen::VectorXd::Zero(M.eigenvalues().size());
  for (Eigen::Index local = 0; local < e.size(); ++local) out[T.mode(local)] += e[local];
  MPI_Allreduce(MPI_IN_PLACE, out.data(), int(out.size()), MPI_DOUBLE, MPI_SUM, comm);
  return out;
}

}  // namespace

StepSizeAdvice slab_advice(MPI_Comm comm, DistributedTransform& T, const Method& method,
                           const System& system, double h, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& p) {
  const HessianBounds kappa = diagonal_hessian_bounds(comm, system, q);
  const Eigen::VectorXd energy = distributed_mode_energies(comm, T, system.M, q, p);
  return advise_step_size(method, system.M.eigenvalues(), h, kappa, {}, energy);
}

}  // namespace erkn::mpi::detail
