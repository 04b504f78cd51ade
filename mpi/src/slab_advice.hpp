// The step-size advisor (erkn/advisor.hpp) at a state distributed over MPI ranks: the blow-up
// guard's likely cause for the distributed integrator (blowup_guard.hpp). Its linear model only: a
// trial run would integrate the whole grid on one process.
#pragma once

#include <mpi.h>

#include <Eigen/Core>

#include "distributed_transform.hpp"
#include "erkn/advisor.hpp"

namespace erkn::mpi::detail {

/// Collective. advise_step_size with M's eigenvalues, the Hessian bounds at q and the mode
/// energies of (q, p) (this rank's parts), each formed over every rank; the same advice on every
/// rank, or the same erkn::Error (a gradient that fails at q) on every rank.
StepSizeAdvice slab_advice(MPI_Comm comm, DistributedTransform& T, const Method& method,
                           const System& system, double h, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& p);

}  // namespace erkn::mpi::detail
