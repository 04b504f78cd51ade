// The grid transforms through FFTW (compiled when erkn is built with ERKN_WITH_FFTW): one
// multi-dimensional r2r plan each way, made once per grid and process and shared by every
// Integrator on that grid (setup then plans nothing: at N = 32 planning from wisdom cost ~6 us,
// more than the rest of the setup). FFTW's planner is not thread-safe (ensembles construct
// integrators on threads), so planning holds one mutex; executing a plan on new arrays of the
// planned alignment (fftw_execute_r2r; every buffer here is fftw_alloc'ed) is thread-safe.
#include <fftw3.h>

#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "erkn/error.hpp"
#include "grid_backend.hpp"

namespace erkn::detail {
namespace {

std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

fftw_r2r_kind forward_kind(GridAxis::Boundary b) {
  switch (b) {
    case GridAxis::Boundary::periodic:
      return FFTW_R2HC;
    case GridAxis::Boundary::dirichlet:
      return FFTW_RODFT00;
    case GridAxis::Boundary::neumann:
      return FFTW_REDFT10;
  }
  return FFTW_R2HC;
}

fftw_r2r_kind inverse_kind(GridAxis::Boundary b) {
  switch (b) {
    case GridAxis::Boundary::periodic:
      return FFTW_HC2R;
    case GridAxis::Boundary::dirichlet:
      return FFTW_RODFT00;
    case GridAxis::Boundary::neumann:
      return FFTW_REDFT01;
  }
  return FFTW_HC2R;
}

// FFTW's logical size N of a kind: inverse(forward(x)) = N x along the axis.
double logical_size(const GridAxis& axis) {
  switch (axis.boundary) {
    case GridAxis::Boundary::periodic:
      return double(axis.n);
    case GridAxis::Boundary::dirichlet:
      return 2.0 * double(axis.n + 1);
    case GridAxis::Boundary::neumann:
      return 2.0 * double(axis.n);
  }
  return 1;
}

struct Plans {
  fftw_plan forward = nullptr, inverse = nullptr;
};

// Every grid's plans, kept for the process and destroyed at its exit (static destruction).
struct PlanCache {
  std::map<std::pair<std::vector<int>, std::vector<int>>, Plans> plans;
  ~PlanCache() {
    for (auto& entry : plans) {
      fftw_destroy_plan(entry.second.forward);
      fftw_destroy_plan(entry.second.inverse);
    }
  }
};

// The plans of a grid (sizes n, forward kinds fk, inverse kinds ik), planned on in/out at the
// first request and kept for the process (a handful of grids).
Plans shared_plans(const std::vector<int>& n, const std::vector<fftw_r2r_kind>& fk,
                   const std::vector<fftw_r2r_kind>& ik, double* in, double* out) {
  static PlanCache cache;
  std::pair<std::vector<int>, std::vector<int>> key{n, std::vector<int>(fk.begin(), fk.end())};
  std::lock_guard lock(planner_mutex());
  if (auto it = cache.plans.find(key); it != cache.plans.end()) return it->second;
  // Out of place; the input is a private copy, so FFTW may destroy it (faster for HC2R).
  // FFTW_MEASURE: erkn_fftw_planner_benchmark measured a transform pair 1.2-3.0x faster than
  // with FFTW_ESTIMATE at 256^2..128^3, for 0.2-1.9 s of planning once per grid and process.
  const unsigned flags = FFTW_MEASURE | FFTW_DESTROY_INPUT;
  Plans plans;
  plans.forward = fftw_plan_r2r(int(n.size()), n.data(), in, out, fk.data(), flags);
  plans.inverse = fftw_plan_r2r(int(n.size()), n.data(), in, out, ik.data(), flags);
  if (!plans.forward || !plans.inverse) {
    if (plans.forward) fftw_destroy_plan(plans.forward);
    if (plans.inverse) fftw_destroy_plan(plans.inverse);
    throw Error("FFTW could not plan the grid transforms");
  }
  return cache.plans.emplace(std::move(key), plans).first->second;
}

struct Buffer {
  explicit Buffer(Eigen::Index d) : data(fftw_alloc_real(std::size_t(d))) {
    if (!data)
      throw Error("FFTW could not allocate a grid buffer of " + std::to_string(d) + " doubles");
  }
  ~Buffer() { fftw_free(data); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  double* data;
};

class FftwBackend final : public GridBackend {
 public:
  explicit FftwBackend(const std::vector<GridAxis>& axes) : d_(size(axes)), in_(d_), out_(d_) {
    std::vector<int> n;
    std::vector<fftw_r2r_kind> fk, ik;
    for (const GridAxis& axis : axes) {
      if (axis.n > std::numeric_limits<int>::max())
        throw Error("FFTW: a grid axis of " + std::to_string(axis.n) + " points is too long");
      n.push_back(int(axis.n));
      fk.push_back(forward_kind(axis.boundary));
      ik.push_back(inverse_kind(axis.boundary));
      scale_ /= logical_size(axis);
    }
    plans_ = shared_plans(n, fk, ik, in_.data, out_.data);
  }

  void forward(const double* x, double* y) override { run(plans_.forward, x, y, 1.0); }
  void inverse(const double* y, double* x) override { run(plans_.inverse, y, x, scale_); }

 private:
  static Eigen::Index size(const std::vector<GridAxis>& axes) {
    Eigen::Index d = 1;
    for (const GridAxis& axis : axes) d *= axis.n;
    return d;
  }

  // to = factor * plan(from): from is copied (r2r plans may overwrite their input); the output
  // goes straight to `to` when its alignment is the planned one (fftw_execute_r2r's rule).
  void run(fftw_plan plan, const double* from, double* to, double factor) {
    Eigen::Map<Eigen::VectorXd>(in_.data, d_) = Eigen::Map<const Eigen::VectorXd>(from, d_);
    Eigen::Map<Eigen::VectorXd> result(to, d_);
    if (fftw_alignment_of(to) == fftw_alignment_of(out_.data)) {
      fftw_execute_r2r(plan, in_.data, to);
      if (factor != 1.0) result *= factor;
    } else {
      fftw_execute_r2r(plan, in_.data, out_.data);
      result = factor * Eigen::Map<const Eigen::VectorXd>(out_.data, d_);
    }
  }

  Eigen::Index d_;
  Buffer in_, out_;
  double scale_ = 1;
  Plans plans_;
};

}  // namespace

std::unique_ptr<GridBackend> make_grid_backend(const std::vector<GridAxis>& axes) {
  return std::make_unique<FftwBackend>(axes);
}
bool grid_backend_is_fftw() { return true; }

}  // namespace erkn::detail
