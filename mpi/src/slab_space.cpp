#include "slab_space.hpp"

#include <exception>

#include "erkn/error.hpp"
#include "erkn/method.hpp"
#include "format.hpp"  // (runtime/src)

namespace erkn::mpi::detail {

void SlabSpace::gradient(const System& system, const Eigen::VectorXd& Q, Eigen::VectorXd& g, int i,
                         const erkn::detail::StepPlace& at, long& evaluations) {
  ++evaluations;
  unchecked_ = true;
  std::string error;
  if (!Q.allFinite()) {
    error = "stage " + std::to_string(i + 1) + " of " + std::string(at.method->name()) +
            " is not finite (is h unstable for this problem?)";
  } else {
    try {
      system.gradient(Q, g);
      if (g.size() != Q.size())
        error = "the gradient callback returned a vector of size " + std::to_string(g.size()) +
                " for a slab of size " + std::to_string(Q.size());
      else if (!g.allFinite())
        error = "the gradient callback returned a non-finite value";
    } catch (const std::exception& e) {
      error = std::string("the gradient callback threw: ") + e.what();
    } catch (...) {
      error = "the gradient callback threw an exception of unknown type";
    }
  }
  if (error.empty()) return;
  g.setZero(Q.size());  // (the transforms stay defined until the next reduce reports it)
  if (error_.empty())
    error_ = error + " at step " + std::to_string(at.step) + " (t = " + erkn::format(at.t) +
             "), stage " + std::to_string(i + 1) + "; the state is unchanged";
}

// g += M Q through the eigenbasis (M is diagonal there): two more transforms per evaluation,
// for RKN methods only.
void SlabSpace::add_MQ(const Eigen::VectorXd& Q, Eigen::VectorXd& g) {
  if (!rkn_) return;
  MQ_hat_.resize(size());
  MQ_.resize(dimension());
  forward(Q, MQ_hat_);
  MQ_hat_ *= T_.eigenvalues();
  inverse(MQ_hat_, MQ_);
  g += MQ_;
}

void SlabSpace::gradient_failed() const {
  std::string mine;
  mine.swap(error_);
  throw_if_any(comm_, mine);
  throw Error("internal: gradient check disagreement");  // (unreachable: some rank failed)
}

}  // namespace erkn::mpi::detail
