// Long runs from Python: a run is cut into chunks that end on grid points (the trajectory and
// the output are those of one call), and between chunks, with the GIL held, Ctrl-C is checked
// (PyErr_CheckSignals: the KeyboardInterrupt leaves the integrator at its last step, the output so
// far kept) and the progress callback is called. Chunks grow from kFirstChunk steps until one lasts
// kChunkSeconds, so the checks cost nothing measurable (python_solve_benchmark.py).
#pragma once

#include <pybind11/pybind11.h>

#include <algorithm>
#include <chrono>

#include "erkn/integrator.hpp"

namespace erkn::python {

namespace py = pybind11;

class LongRun {
 public:
  static constexpr long kFirstChunk = 4096;
  static constexpr double kChunkSeconds = 0.05;

  /// progress: None or a callable progress(t), called between chunks and at the end.
  explicit LongRun(py::object progress) : progress_(std::move(progress)) {}

  /// Calls chunk(t_c, every_c) for grid points t_c, then chunk(t_end, every), each returning
  /// true to stop (a terminal event); between them, Ctrl-C and progress. A chunk starts on an
  /// output step (a multiple of `every` steps from the start) and holds whole output intervals
  /// (every_c = every), or it lies within one interval and observes its end only if that end is
  /// an output step (every_c = its length; else every_c = 0: no observer). So the output is that
  /// of one call. Returns chunk's last answer.
  template <class Chunk>
  bool to(const Integrator& run, double t_end, long every, Chunk&& chunk) {
    for (long done = 0;;) {
      const long to_output = every - done % every, k = chunk_size(to_output, every);
      const double t_c = run.t() + double(k) * run.h();
      if (run.steps_until(t_end) <= k || run.steps_until(t_c) != k) break;
      const auto start = std::chrono::steady_clock::now();
      const long every_c = to_output == every && k >= every ? every : k == to_output ? k : 0;
      if (chunk(t_c, every_c)) return true;
      done += k;
      grow(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      between(run.t());
    }
    const bool stopped = chunk(t_end, every);
    if (!progress_.is_none()) progress_(run.t());
    return stopped;
  }

  /// n steps of run as calls f(k) of chunks, with Ctrl-C and progress between them.
  template <class F>
  void steps(const Integrator& run, long n, F&& f) {
    for (; n > size_; between(run.t())) {
      const auto start = std::chrono::steady_clock::now();
      f(size_);
      n -= size_;
      grow(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    f(n);
  }

 private:
  py::object progress_;
  long size_ = kFirstChunk;

  // Whole output intervals from an output step, else up to the next output step.
  long chunk_size(long to_output, long every) const {
    if (to_output == every && every <= size_) return size_ / every * every;
    return std::min(size_, to_output);
  }
  void grow(double seconds) {
    if (seconds < kChunkSeconds / 2 && size_ < (1L << 40)) size_ *= 2;
  }
  // With the GIL: a pending Ctrl-C raises KeyboardInterrupt here; then progress(t).
  void between(double t) {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!progress_.is_none()) progress_(t);
  }
};

}  // namespace erkn::python
