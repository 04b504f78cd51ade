// The grid transforms through FFTW (compiled when erkn is built with ERKN_WITH_FFTW): per grid
// one multi-dimensional plan each way, r2r (GridBackend) or, where every axis is periodic, r2c and
// c2r (HalfSpectrumBackend), made once per grid and process and shared by every Integrator on
// that grid (setup then plans nothing: at N = 32 planning from wisdom cost ~6 us, more than the
// rest of the setup). FFTW's planner is not thread-safe (ensembles construct integrators on
// threads), so planning holds one mutex; executing a plan on new arrays of the planned alignment
// (fftw_execute_r2r, fftw_execute_dft_r2c/c2r; every buffer here is fftw_alloc'ed) is thread-safe.
#include <fftw3.h>
#include <unistd.h>  // (getpid)

#include <complex>
#include <cstdio>
#include <cstdlib>
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

// A grid's plans by its sizes and r2r kinds (forward kinds; none: r2c/c2r).
using PlanKey = std::pair<std::vector<int>, std::vector<int>>;

// Every grid's plans, kept for the process and destroyed at its exit (static destruction).
struct PlanCache {
  std::map<PlanKey, Plans> plans;
  ~PlanCache() {
    for (auto& entry : plans) {
      fftw_destroy_plan(entry.second.forward);
      fftw_destroy_plan(entry.second.inverse);
    }
  }
};

// FFTW_MEASURE times candidate algorithms, so two processes may pick different plans for one
// grid, whose round-off differs: implicit runs then differ between processes in their results
// and iteration counts (sine-Gordon N = 2048, h = 1/100, 100 steps: SERKN3s4(1) 1295 or 1368
// gradient evaluations in runs of one binary). FFTW's remedy is wisdom, the plans recorded:
// the file named by the environment variable ERKN_FFTW_WISDOM is imported before each new plan
// of a process, and every new plan is added to it (written to a file of the process, then renamed
// over it, so concurrent processes never read a partial file). Processes sharing the file plan
// alike, and plan in microseconds. (FFTW_ESTIMATE plans alike in every process too, but its
// 1-D r2c + c2r pair took 2.0x the time of MEASURE's at N = 512, 1.25x at 2048 and 8192: a
// stand-alone driver, medians of 7.) Unset: each process measures for itself.
// (Set but empty counts as unset: it named no file, and the export left ".<pid>" files behind.)
const char* wisdom_file() {
  const char* file = std::getenv("ERKN_FFTW_WISDOM");
  return file && *file ? file : nullptr;
}

// Before each new plan, not once per process: a process that imported the file before another
// wrote a size would measure that size for itself and then replace the other's plan in the file
// (python_solve_benchmark.py with a fresh file: erkn.solve and its C++ server exported different
// N = 2048 plans in the first run, and so ran different transforms).
void import_wisdom() {
  if (const char* file = wisdom_file()) fftw_import_wisdom_from_filename(file);
}

void export_wisdom() {
  const char* file = wisdom_file();
  if (!file) return;
  const std::string own = std::string(file) + "." + std::to_string(getpid());
  if (fftw_export_wisdom_to_filename(own.c_str())) std::rename(own.c_str(), file);
}

// FFTW's sizes of the axes (int), refusing an axis too long for them.
std::vector<int> fftw_sizes(const std::vector<GridAxis>& axes) {
  std::vector<int> n;
  for (const GridAxis& axis : axes) {
    if (axis.n > std::numeric_limits<int>::max())
      throw Error("FFTW: a grid axis of " + std::to_string(axis.n) + " points is too long");
    n.push_back(int(axis.n));
  }
  return n;
}

// True when `key` is that of the grid `axes` with the forward kinds `kinds` (compared without
// building it).
bool same_grid(const PlanKey& key, const std::vector<GridAxis>& axes,
               const std::vector<int>& kinds) {
  if (key.first.size() != axes.size() || key.second != kinds) return false;
  for (std::size_t a = 0; a < axes.size(); ++a)
    if (key.first[a] != axes[a].n) return false;
  return true;
}

// The plans of the grid `axes` with the forward kinds `kinds` (none: r2c/c2r), made by
// make(sizes) at the first request and kept for the process (a handful of grids). FFTW_MEASURE:
// erkn_fftw_planner_benchmark measured a transform pair 1.2-3.0x faster than with FFTW_ESTIMATE at
// 256^2..128^3, for 0.2-1.9 s of planning once per grid and process (without wisdom). A thread's
// request for the grid it asked for last is answered from that entry (the cache's entries stay
// put until the process exits), without building the key, locking the mutex or walking the map.
template <class Make>
Plans shared_plans(const std::vector<GridAxis>& axes, const std::vector<int>& kinds, Make&& make) {
  static PlanCache cache;
  thread_local const std::pair<const PlanKey, Plans>* last = nullptr;
  if (last && same_grid(last->first, axes, kinds)) return last->second;
  PlanKey key{fftw_sizes(axes), kinds};
  std::lock_guard lock(planner_mutex());
  auto it = cache.plans.find(key);
  if (it == cache.plans.end()) {
    import_wisdom();
    const Plans plans = make(key.first);
    if (!plans.forward || !plans.inverse) {
      if (plans.forward) fftw_destroy_plan(plans.forward);
      if (plans.inverse) fftw_destroy_plan(plans.inverse);
      throw Error("FFTW could not plan the grid transforms");
    }
    export_wisdom();
    it = cache.plans.emplace(std::move(key), plans).first;
  }
  last = &*it;
  return it->second;
}

Eigen::Index size(const std::vector<GridAxis>& axes) {
  Eigen::Index d = 1;
  for (const GridAxis& axis : axes) d *= axis.n;
  return d;
}

// An FFTW-aligned array of n T (double or fftw_complex), or none.
template <class T>
struct Buffer {
  Buffer() = default;
  explicit Buffer(Eigen::Index n)
      : data(static_cast<T*>(fftw_malloc(sizeof(T) * std::size_t(std::max<Eigen::Index>(n, 1))))) {
    if (!data)
      throw Error("FFTW could not allocate a grid buffer of " + std::to_string(n) + " numbers");
  }
  ~Buffer() { fftw_free(data); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(Buffer&& o) noexcept {
    std::swap(data, o.data);
    return *this;
  }
  T* data = nullptr;
};

// True when p has the alignment of the planned array `planned` (fftw_execute_*'s rule).
template <class T>
bool planned_alignment(const T* p, T* planned) {
  return fftw_alignment_of(reinterpret_cast<double*>(const_cast<T*>(p))) ==
         fftw_alignment_of(reinterpret_cast<double*>(planned));
}

// planned_alignment(p, planned) for one planned array, remembering the answer for the last p: a
// stepper transforms the same arrays every step (two calls into FFTW per check otherwise, ~1 % of
// a run at N = 32).
template <class T>
class PlannedAlignment {
 public:
  explicit PlannedAlignment(T* planned) : planned_(planned) {}
  bool operator()(const T* p) {
    if (p != last_) last_ = p, ok_ = planned_alignment(p, planned_);
    return ok_;
  }

 private:
  T* planned_;
  const T* last_ = nullptr;
  bool ok_ = false;
};

class FftwBackend final : public GridBackend {
 public:
  explicit FftwBackend(const std::vector<GridAxis>& axes) : d_(size(axes)), in_(d_), out_(d_) {
    std::vector<fftw_r2r_kind> fk, ik;
    for (const GridAxis& axis : axes) {
      fk.push_back(forward_kind(axis.boundary));
      ik.push_back(inverse_kind(axis.boundary));
      scale_ /= logical_size(axis);
    }
    // Out of place; the input is a private copy, so FFTW may destroy it (faster for HC2R).
    const unsigned flags = FFTW_MEASURE | FFTW_DESTROY_INPUT;
    plans_ = shared_plans(axes, std::vector<int>(fk.begin(), fk.end()), [&](std::vector<int>& n) {
      const int rank = int(n.size());
      return Plans{fftw_plan_r2r(rank, n.data(), in_.data, out_.data, fk.data(), flags),
                   fftw_plan_r2r(rank, n.data(), in_.data, out_.data, ik.data(), flags)};
    });
  }

  void forward(const double* x, double* y) override { run(plans_.forward, x, y, 1.0); }
  void inverse(const double* y, double* x) override { run(plans_.inverse, y, x, scale_); }

 private:
  // to = factor * plan(from): from is copied (r2r plans may overwrite their input); the output
  // goes straight to `to` when its alignment is the planned one (fftw_execute_r2r's rule).
  void run(fftw_plan plan, const double* from, double* to, double factor) {
    Eigen::Map<Eigen::VectorXd>(in_.data, d_) = Eigen::Map<const Eigen::VectorXd>(from, d_);
    Eigen::Map<Eigen::VectorXd> result(to, d_);
    if (planned_alignment(to, out_.data)) {
      fftw_execute_r2r(plan, in_.data, to);
      if (factor != 1.0) result *= factor;
    } else {
      fftw_execute_r2r(plan, in_.data, out_.data);
      result = factor * Eigen::Map<const Eigen::VectorXd>(out_.data, d_);
    }
  }

  Eigen::Index d_;
  Buffer<double> in_, out_;
  double scale_ = 1;
  Plans plans_;
};

class FftwHalfSpectrum final : public HalfSpectrumBackend {
 public:
  explicit FftwHalfSpectrum(const std::vector<GridAxis>& axes)
      : d_(size(axes)), m_(half_spectrum_size(axes)), spectrum_(m_) {
    plans_ = shared_plans(axes, {}, [&](std::vector<int>& n) {
      const int rank = int(n.size());
      const Buffer<double> real(d_);  // (planned on, as every later array: fftw_malloc'ed)
      // r2c keeps its input (FFTW's default out of place), so forward reads the caller's x;
      // c2r may destroy it (its default), inverse gives it a scaled copy. Both measured (1-D,
      // thread CPU time, medians of 15 rounds), N = 512 / 2048 / 8192: r2c 0.38 / 1.83 / 9.8 us
      // against 0.47 / 2.04 / 10.3 with a copy and FFTW_DESTROY_INPUT; c2r after a scaled copy
      // 0.49 / 2.06 / 10.6 us against 0.72 / 2.69 / 12.9 preserving its input, then scaled.
      return Plans{fftw_plan_dft_r2c(rank, n.data(), real.data, spectrum_.data, FFTW_MEASURE),
                   fftw_plan_dft_c2r(rank, n.data(), spectrum_.data, real.data,
                                     FFTW_MEASURE | FFTW_DESTROY_INPUT)};
    });
  }

  // Straight from x to y when both have the planned alignment (no copy), else through buffers.
  void forward(const double* x, std::complex<double>* y) override {
    auto* out = reinterpret_cast<fftw_complex*>(y);
    if (real_aligned_(x) && spectrum_aligned_(out)) {
      fftw_execute_dft_r2c(plans_.forward, const_cast<double*>(x), out);
      return;
    }
    Eigen::Map<Eigen::VectorXd>(real(), d_) = Eigen::Map<const Eigen::VectorXd>(x, d_);
    fftw_execute_dft_r2c(plans_.forward, real(), spectrum_.data);
    complex_map(out) = complex_map(spectrum_.data);
  }

  // y / d into the buffer c2r may destroy (the copy and the normalisation in one pass), then
  // straight to x when it has the planned alignment.
  void inverse(const std::complex<double>* y, double* x) override {
    complex_map(spectrum_.data) = scale() * Eigen::Map<const Eigen::VectorXcd>(y, m_);
    inverse_staged(x);
  }
  // The staged y / d is that buffer (the explicit stepper's flow writes it: no copy pass).
  std::complex<double>* staging() override {
    return reinterpret_cast<std::complex<double>*>(spectrum_.data);
  }
  double staging_scale() const override { return scale(); }
  void inverse_staged(double* x) override {
    if (output_aligned_(x)) {
      fftw_execute_dft_c2r(plans_.inverse, spectrum_.data, x);
      return;
    }
    fftw_execute_dft_c2r(plans_.inverse, spectrum_.data, real());
    Eigen::Map<Eigen::VectorXd>(x, d_) = Eigen::Map<const Eigen::VectorXd>(real(), d_);
  }

  // Straight from y (c2r may destroy it) when y and x have the planned alignment: get_state's
  // q and p, scaled by its pass into the stepper's own arrays, need no copy pass into the buffer,
  // and the buffer keeps the stage the stepper staged there.
  bool inverse_scaled(std::complex<double>* y, double* x) override {
    auto* in = reinterpret_cast<fftw_complex*>(y);
    if (scaled_aligned_(in) && output_aligned_(x)) {
      fftw_execute_dft_c2r(plans_.inverse, in, x);
      return true;
    }
    complex_map(spectrum_.data) = Eigen::Map<const Eigen::VectorXcd>(y, m_);
    inverse_staged(x);
    return false;
  }

  // The plans executed straight on arrays of the planned alignment (others through the buffers,
  // as forward and inverse_staged do). callgrind, integrate of sine-Gordon N = 32 Strang: 57
  // instructions fewer per gradient than a virtual call and alignment check per transform (5446
  // -> 5389 per step, ~1280 of them in FFTW).
  BoundTransform bind_forward(const double* x, std::complex<double>* y) override {
    if (!real_aligned_(x) || !spectrum_aligned_(reinterpret_cast<fftw_complex*>(y)))
      return HalfSpectrumBackend::bind_forward(x, y);
    return {[](void* plan, const void* in, void* out) {
              fftw_execute_dft_r2c(static_cast<fftw_plan>(plan),
                                   const_cast<double*>(static_cast<const double*>(in)),
                                   static_cast<fftw_complex*>(out));
            },
            plans_.forward, x, y};
  }
  BoundTransform bind_inverse_staged(double* x) override {
    if (!output_aligned_(x)) return HalfSpectrumBackend::bind_inverse_staged(x);
    return {[](void* plan, const void* in, void* out) {
              fftw_execute_dft_c2r(static_cast<fftw_plan>(plan),
                                   static_cast<fftw_complex*>(const_cast<void*>(in)),
                                   static_cast<double*>(out));
            },
            plans_.inverse, spectrum_.data, x};
  }

 private:
  double scale() const { return 1 / double(d_); }
  Eigen::Map<Eigen::VectorXcd> complex_map(fftw_complex* z) const {
    return {reinterpret_cast<std::complex<double>*>(z), m_};
  }
  // The real buffer of the transforms through buffers, allocated at the first (a stepper's arrays
  // have the planned alignment: its memalign and free were ~900 of the ~14,000 instructions of a
  // construction and destruction at sine-Gordon N = 32, callgrind).
  double* real() {
    if (!real_.data) real_ = Buffer<double>(d_);
    return real_.data;
  }

  Eigen::Index d_, m_;
  Buffer<double> real_;  // (none until real())
  Buffer<fftw_complex> spectrum_;
  Plans plans_;
  // (forward's input and output, inverse's output, inverse_scaled's input; the planned alignment
  // of a real array is that of every fftw_malloc'ed one, spectrum_'s)
  double* planned_real_ = reinterpret_cast<double*>(spectrum_.data);
  PlannedAlignment<double> real_aligned_{planned_real_}, output_aligned_{planned_real_};
  PlannedAlignment<fftw_complex> spectrum_aligned_{spectrum_.data}, scaled_aligned_{spectrum_.data};
};

}  // namespace

std::unique_ptr<GridBackend> make_grid_backend(const std::vector<GridAxis>& axes) {
  return std::make_unique<FftwBackend>(axes);
}
bool grid_backend_is_fftw() { return true; }

bool half_spectrum_available(const std::vector<GridAxis>& axes) {
  for (const GridAxis& axis : axes)
    if (axis.boundary != GridAxis::Boundary::periodic) return false;
  return !axes.empty();
}

std::unique_ptr<HalfSpectrumBackend> make_half_spectrum_backend(const std::vector<GridAxis>& axes) {
  if (!half_spectrum_available(axes)) throw Error("no real-to-complex transform for these axes");
  return std::make_unique<FftwHalfSpectrum>(axes);
}

}  // namespace erkn::detail
