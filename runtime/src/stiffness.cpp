#include "erkn/stiffness.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <new>
#include <numbers>
#include <string>

#include "erkn/error.hpp"
#include "format.hpp"

namespace erkn {

struct Stiffness::Data {
  Structure structure;
  Eigen::Index dim = 0;
  Eigen::VectorXd eigenvalues, entries;
  Eigen::MatrixXd eigenvectors, matrix;
  Eigen::VectorXi nonzeros;
  std::vector<GridAxis> axes;
  double shift = 0;
};

namespace {

void require_finite(const Eigen::Ref<const Eigen::MatrixXd>& m, const char* what) {
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      if (!std::isfinite(m(i, j)))
        throw Error(std::string(what) + " has a non-finite entry " + format(m(i, j)) + " at (" +
                    std::to_string(i) + ", " + std::to_string(j) + ")");
}

// Sets eigenvalues in [-tol * max|lambda|, 0) to 0; throws for anything more negative.
void require_psd(Eigen::VectorXd& lambda, const char* what) {
  const double scale = lambda.cwiseAbs().maxCoeff();
  Eigen::Index k;
  const double low = lambda.minCoeff(&k);
  if (low < -Stiffness::kTolerance * scale)
    throw Error(std::string(what) + " is not positive semi-definite: eigenvalue " +
                std::to_string(k) + " is " + format(low) + " (relative " + format(low / scale) +
                " of the largest |eigenvalue|; tolerance " + format(Stiffness::kTolerance) + ")");
  lambda = lambda.cwiseMax(0.0);
}

}  // namespace

Stiffness Stiffness::scalar(double omega2) {
  if (!std::isfinite(omega2))
    throw Error("M = omega2*I: omega2 = " + format(omega2) + " is not finite");
  if (omega2 < 0)
    throw Error("M = omega2*I is not positive semi-definite: omega2 = " + format(omega2));
  const auto make = [](double w2) {
    auto d = std::make_shared<Data>();
    d->structure = Structure::scalar;
    d->eigenvalues = Eigen::VectorXd::Constant(1, w2);  // (also its entries: see entries())
    return d;
  };
  // M = 0 (System's default) shares one record: a default System allocates nothing.
  static const std::shared_ptr<const Data> zero = make(0.0);
  return Stiffness(omega2 == 0 && !std::signbit(omega2) ? zero : make(omega2));
}

Stiffness Stiffness::diagonal(const Eigen::VectorXd& m) {
  if (m.size() == 0) throw Error("diagonal M is empty");
  require_finite(m, "diagonal M");
  auto d = std::make_shared<Data>();
  d->structure = Structure::diagonal;
  d->dim = m.size();
  d->eigenvalues = d->entries = m;
  require_psd(d->eigenvalues, "diagonal M");
  return Stiffness(d);
}

Stiffness Stiffness::circulant(const Eigen::VectorXd& col) {
  const Eigen::Index n = col.size();
  if (n == 0) throw Error("circulant M: the first column is empty");
  require_finite(col, "circulant M's first column");
  const double scale = col.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 1; j < n; ++j)
    if (std::abs(col[j] - col[n - j]) > kTolerance * scale)
      throw Error("circulant M is not symmetric: first column entries " + std::to_string(j) +
                  " and " + std::to_string(n - j) + " differ by " + format(col[j] - col[n - j]) +
                  " (relative " + format((col[j] - col[n - j]) / scale) + "; tolerance " +
                  format(kTolerance) + ")");
  auto d = std::make_shared<Data>();
  d->structure = Structure::circulant;
  d->dim = n;
  d->entries = col;
  std::vector<int> nz;
  for (Eigen::Index j = 0; j < n; ++j)
    if (col[j] != 0) nz.push_back(int(j));
  d->nonzeros = Eigen::Map<Eigen::VectorXi>(nz.data(), Eigen::Index(nz.size()));
  // lambda_k = sum_j col[j] cos(2 pi j k / N), with the angle reduced exactly to (j k) mod N.
  Eigen::VectorXd cosine(n);
  for (Eigen::Index m = 0; m < n; ++m)
    cosine[m] = std::cos(2 * std::numbers::pi * double(m) / double(n));
  d->eigenvalues.resize(n / 2 + 1);
  for (Eigen::Index k = 0; k <= n / 2; ++k) {
    double sum = 0;
    for (int j : nz) sum += col[j] * cosine[(j * k) % n];
    d->eigenvalues[k] = sum;
  }
  require_psd(d->eigenvalues, "circulant M");
  return Stiffness(d);
}

Stiffness Stiffness::dense(const Eigen::MatrixXd& m) {
  if (m.rows() != m.cols())
    throw Error("dense M must be square; it is " + std::to_string(m.rows()) + "x" +
                std::to_string(m.cols()));
  if (m.size() == 0) throw Error("dense M is empty");
  require_finite(m, "dense M");
  const double scale = m.cwiseAbs().maxCoeff();
  Eigen::Index i, j;
  const double asym = (m - m.transpose()).cwiseAbs().maxCoeff(&i, &j);
  if (asym > kTolerance * scale)
    throw Error("dense M is not symmetric: |M(" + std::to_string(i) + "," + std::to_string(j) +
                ") - M(" + std::to_string(j) + "," + std::to_string(i) + ")| = " + format(asym) +
                " (relative " + format(asym / scale) + "; tolerance " + format(kTolerance) + ")");
  auto d = std::make_shared<Data>();
  d->structure = Structure::dense;
  d->dim = m.rows();
  d->matrix = 0.5 * (m + m.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(d->matrix);
  if (eig.info() != Eigen::Success) throw Error("dense M: the eigendecomposition failed");
  d->eigenvalues = eig.eigenvalues();
  d->eigenvectors = eig.eigenvectors();
  require_psd(d->eigenvalues, "dense M");
  return Stiffness(d);
}

GridAxis::Boundary GridAxis::boundary_named(const std::string& name) {
  if (name == "periodic") return Boundary::periodic;
  if (name == "dirichlet") return Boundary::dirichlet;
  if (name == "neumann") return Boundary::neumann;
  throw Error("unknown boundary '" + name + "' (periodic, dirichlet or neumann)");
}

Eigen::VectorXd GridAxis::eigenvalues() const {
  using std::numbers::pi;
  const double scale = 4 / (spacing * spacing);
  Eigen::VectorXd mu(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    double angle = 0;  // the argument of sin^2
    switch (boundary) {
      case Boundary::periodic:
        angle = pi * double(std::min(k, n - k)) / double(n);
        break;
      case Boundary::dirichlet:
        angle = pi * double(k + 1) / double(2 * (n + 1));
        break;
      case Boundary::neumann:
        angle = pi * double(k) / double(2 * n);
        break;
    }
    const double sine = std::sin(angle);
    mu[k] = scale * sine * sine;
  }
  return mu;
}

namespace {

void require_axis(const GridAxis& axis, std::size_t a) {
  const std::string name = "grid M: axis " + std::to_string(a);
  if (axis.n < 1)
    throw Error(name + " has n = " + std::to_string(axis.n) + " unknowns (need >= 1)");
  if (!std::isfinite(axis.spacing) || axis.spacing <= 0)
    throw Error(name + " has spacing " + format(axis.spacing) + " (need finite and > 0)");
  // Its eigenvalues reach 4 / spacing^2: an overflow there would make them inf (and 0 * inf NaN).
  if (!std::isfinite(4 / (axis.spacing * axis.spacing)))
    throw Error(name + " has spacing " + format(axis.spacing) +
                ": its eigenvalues 4 / spacing^2 overflow a double");
  switch (axis.boundary) {
    case GridAxis::Boundary::periodic:
    case GridAxis::Boundary::dirichlet:
    case GridAxis::Boundary::neumann:
      return;
  }
  throw Error(name + " has an unknown boundary condition");
}

// lambda(k_0, ..., k_{K-1}) = shift + sum_a mu_a[k_a], built one axis at a time (row-major).
Eigen::VectorXd grid_eigenvalues(const std::vector<GridAxis>& axes, double shift) {
  Eigen::VectorXd lambda = Eigen::VectorXd::Constant(1, shift);
  for (const GridAxis& axis : axes) {
    const Eigen::VectorXd mu = axis.eigenvalues();
    Eigen::VectorXd next(lambda.size() * axis.n);
    for (Eigen::Index i = 0; i < lambda.size(); ++i)
      next.segment(i * axis.n, axis.n) = mu.array() + lambda[i];
    lambda.swap(next);
  }
  return lambda;
}

}  // namespace

Stiffness Stiffness::grid(std::vector<GridAxis> axes, double shift) {
  if (axes.empty()) throw Error("grid M needs at least one axis");
  if (!std::isfinite(shift)) throw Error("grid M: the shift " + format(shift) + " is not finite");
  Eigen::Index dim = 1;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    require_axis(axes[a], a);
    if (dim > std::numeric_limits<Eigen::Index>::max() / axes[a].n)
      throw Error("grid M: the number of unknowns overflows");
    dim *= axes[a].n;
  }
  auto d = std::make_shared<Data>();
  d->structure = Structure::grid;
  d->dim = dim;
  d->shift = shift;
  try {
    d->eigenvalues = grid_eigenvalues(axes, shift);
  } catch (const std::bad_alloc&) {
    throw Error("grid M: " + std::to_string(dim) + " unknowns (" + format(8.0 * double(dim)) +
                " bytes per vector) cannot be allocated");
  }
  require_finite(d->eigenvalues, "grid M's eigenvalues");
  require_psd(d->eigenvalues, "grid M");
  d->axes = std::move(axes);
  return Stiffness(d);
}

Stiffness::Structure Stiffness::structure() const { return data_->structure; }
Eigen::Index Stiffness::dim() const { return data_->dim; }
const Eigen::VectorXd& Stiffness::eigenvalues() const { return data_->eigenvalues; }
const Eigen::MatrixXd& Stiffness::eigenvectors() const { return data_->eigenvectors; }
const Eigen::VectorXd& Stiffness::entries() const {
  return data_->structure == Structure::scalar ? data_->eigenvalues : data_->entries;
}
const Eigen::MatrixXd& Stiffness::matrix() const { return data_->matrix; }
const Eigen::VectorXi& Stiffness::nonzeros() const { return data_->nonzeros; }
const std::vector<GridAxis>& Stiffness::axes() const { return data_->axes; }
double Stiffness::shift() const { return data_->shift; }

namespace {

// The dense grid M: shift on the diagonal, then each axis's stencil (-1, 2, -1) / spacing^2
// along its lines, with the boundary's neighbour rule (accumulated, so n = 1, 2 come out right).
Eigen::MatrixXd grid_to_dense(const std::vector<GridAxis>& axes, double shift, Eigen::Index d) {
  Eigen::MatrixXd m = shift * Eigen::MatrixXd::Identity(d, d);
  Eigen::Index inner = d;  // the stride of axis a: product of n over the axes after it
  for (const GridAxis& axis : axes) {
    const Eigen::Index n = axis.n;
    inner /= n;
    const double w = 1 / (axis.spacing * axis.spacing);
    for (Eigen::Index i = 0; i < d; ++i) {
      const Eigen::Index j = (i / inner) % n;  // i's index along this axis
      m(i, i) += 2 * w;
      for (const Eigen::Index step : {Eigen::Index(-1), Eigen::Index(1)}) {
        Eigen::Index k = j + step;  // the neighbour's index along the axis
        if (k < 0 || k >= n) {
          if (axis.boundary == GridAxis::Boundary::dirichlet) continue;  // x = 0 outside
          if (axis.boundary == GridAxis::Boundary::neumann) k = j;       // mirrored: x_{-1} = x_0
          if (axis.boundary == GridAxis::Boundary::periodic) k = (k + n) % n;
        }
        m(i, i + (k - j) * inner) -= w;
      }
    }
  }
  return m;
}

}  // namespace

Eigen::MatrixXd Stiffness::to_dense(Eigen::Index d) const {
  switch (data_->structure) {
    case Structure::scalar:
      return data_->eigenvalues[0] * Eigen::MatrixXd::Identity(d, d);
    case Structure::diagonal:
      return data_->entries.asDiagonal();
    case Structure::dense:
      return data_->matrix;
    case Structure::circulant: {
      const Eigen::Index n = data_->dim;
      Eigen::MatrixXd m(n, n);
      for (Eigen::Index k = 0; k < n; ++k)
        for (Eigen::Index i = 0; i < n; ++i) m(i, k) = data_->entries[(i - k + n) % n];
      return m;
    }
    case Structure::grid:
      return grid_to_dense(data_->axes, data_->shift, data_->dim);
  }
  return {};
}

}  // namespace erkn
