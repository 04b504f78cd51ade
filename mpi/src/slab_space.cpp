#include "slab_space.hpp"

#include <exception>
#include <utility>

#include "erkn/error.hpp"
#include "erkn/method.hpp"
#include "format.hpp"  // (runtime/src)

namespace erkn::mpi::detail {

void SlabSpace::gradient(const System& system, const Eigen::VectorXd& Q, Eigen::VectorXd& g, int i,
                         const erkn::detail::StepPlace& at, long& evaluations) {
  ++evaluations;
  unchecked_ = true;
  std::string error;
  using erkn::detail::all_finite;  // (vectorised, no early exit: stage_checks.hpp)
  if (!all_finite(Q.data(), Q.size())) {
    error = "stage " + std::to_string(i + 1) + " of " + std::string(at.method->name()) +
            " is not finite (is h unstable for this problem?)";
  } else {
    try {
      system.gradient(Q, g);
      if (g.size() != Q.size())
        error = "the gradient callback returned a vector of size " + std::to_string(g.size()) +
                " for a slab of size " + std::to_string(Q.size());
      else if (!all_finite(g.data(), g.size()))
        error = "the gradient callback returned a non-finite value";
    } catch (const std::exception& e) {
      error = std::string("the gradient callback threw: ") + e.what();
    } catch (...) {
      error = "the gradient callback threw an exception of unknown type";
    }
  }
  if (error.empty()) return;
  g.setZero(Q.size());  // (the transforms stay defined until the next reduce reports it)
  keep(error + " at step " + std::to_string(at.step) + " (t = " + erkn::format(at.t) + "), stage " +
       std::to_string(i + 1) + "; the state is unchanged");
}

void SlabSpace::defer(const std::exception& e) { keep(message_of(e)); }

void SlabSpace::keep(std::string message) {
  unchecked_ = true;
  if (error_.empty()) error_ = std::move(message);
}

// g += M Q for RKN methods only: two more transforms per evaluation.
void SlabSpace::add_MQ(const Eigen::VectorXd& Q, Eigen::VectorXd& g) {
  if (!rkn_) return;
  MQ_.resize(dimension());
  apply_M(Q, MQ_);
  g += MQ_;
}

void SlabSpace::apply_M(const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  MQ_hat_.resize(size());
  y.resize(dimension());
  forward(x, MQ_hat_);
  MQ_hat_ *= T_.eigenvalues();
  inverse(MQ_hat_, y);
}

void SlabSpace::gradient_failed() const {
  std::string mine;
  mine.swap(error_);
  throw_if_any(comm_, mine);
  throw Error("internal: gradient check disagreement");  // (unreachable: some rank failed)
}

}  // namespace erkn::mpi::detail
