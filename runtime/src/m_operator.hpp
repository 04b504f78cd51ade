// y = M x for every Stiffness form, without allocating: scalar and diagonal elementwise, dense
// one matrix-vector product, circulant a direct stencil when the first column has few nonzeros
// (nnz <= 2 log2 N) and otherwise an FFT product with the closed-form eigenvalues; grid its
// stencil along each axis (O(d)).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "erkn/stiffness.hpp"
#include "transforms.hpp"

namespace erkn::detail {

class MOperator {
 public:
  MOperator(const Stiffness& M, Eigen::Index d);
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y);

 private:
  void apply_grid(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;

  Stiffness M_;
  std::unique_ptr<HalfSpectrumTransform> fft_;  // set for a circulant M applied through the FFT
  Eigen::ArrayXcd spectrum_;
};

}  // namespace erkn::detail
