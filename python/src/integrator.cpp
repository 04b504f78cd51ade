// erkn.Integrator: the runtime's Integrator over a System from Python. Loops run in C++ and
// collect their output into arrays handed to NumPy without a copy; with built-in potentials
// the GIL is released while stepping (but for runs of a few microseconds: releases_gil).
#include "erkn/integrator.hpp"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <structmember.h>

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "bindings.hpp"
#include "erkn/error.hpp"
#include "events.hpp"
#include "long_run.hpp"
#include "system.hpp"

namespace erkn::python {
namespace {

// `value` moved to the heap and the capsule that deletes it, the base of NumPy arrays on it. (A
// plain PyCapsule: pybind11's capsule with a destructor keeps it in the context and saves and
// restores the error state around it, ~150 instructions more per capsule.)
template <class T>
std::pair<T*, py::capsule> owned(T&& value) {
  auto heap = std::make_unique<T>(std::move(value));
  PyObject* const capsule = PyCapsule_New(heap.get(), nullptr, [](PyObject* c) {
    delete static_cast<T*>(PyCapsule_GetPointer(c, nullptr));
  });
  if (!capsule) throw py::error_already_set();
  return {heap.release(), py::reinterpret_steal<py::capsule>(capsule)};
}

// A C-order float64 array of shape (rows) (cols < 0) or (rows, cols) on `data` (no copy), which
// `base` keeps alive. NumPy's C API through pybind11's table: py::array_t's constructor builds
// its shape and strides in heap vectors (callgrind: ~1.2k instructions an array).
py::object array_on(double* data, py::ssize_t rows, py::ssize_t cols, const py::capsule& base) {
  auto& api = py::detail::npy_api::get();
  Py_intptr_t shape[2] = {rows, cols};
  PyObject* a = api.PyArray_NewFromDescr_(
      api.PyArray_Type_, api.PyArray_DescrFromType_(py::detail::npy_api::NPY_DOUBLE_),
      cols < 0 ? 1 : 2, shape, nullptr, data, data ? py::detail::npy_api::NPY_ARRAY_WRITEABLE_ : 0,
      nullptr);
  if (!a) throw py::error_already_set();
  auto array = py::reinterpret_steal<py::object>(a);
  if (data && api.PyArray_SetBaseObject_(a, base.inc_ref().ptr()) != 0)
    throw py::error_already_set();
  return array;
}

// The capsule that deletes `block` (new[]), the base of NumPy arrays on it.
py::capsule owning(std::unique_ptr<double[]> block) {
  PyObject* const capsule = PyCapsule_New(block.get(), nullptr, [](PyObject* c) {
    delete[] static_cast<double*>(PyCapsule_GetPointer(c, nullptr));
  });
  if (!capsule) throw py::error_already_set();
  block.release();
  return py::reinterpret_steal<py::capsule>(capsule);
}

// A run's result: arrays t (n), q and p (n, d), energies (n) or None, the events' zeros or None,
// and whether a terminal event stopped the run. (erkn.solve reads it in C++; Integrator.run
// returns it as a tuple: no tuple made and freed per solve, ~200 instructions.)
struct RunResult {
  py::object t, q, p, energy, hits;
  bool stopped = false;
  py::tuple as_tuple() const { return py::make_tuple(t, q, p, energy, hits, stopped); }
};

// Output of a run: times, states and (with energies) H, row k for time k, in one block of
// `capacity` rows laid out t | q | p | H, doubled when full: one allocation, which the arrays'
// capsule owns itself, where a vector for each and the struct holding them took four or five
// (callgrind, 1-step Duffing Strang erkn.solve: 10.5k -> 9.7k instructions).
class Output {
 public:
  /// Room for `rows` rows (>= 1 kept) at first.
  Output(Eigen::Index d, bool energy, long rows) : d_(d), energy_(energy) {
    grow(std::max(rows, 1L));
  }
  void add(const Integrator& run, double tk, const Eigen::VectorXd& qk, const Eigen::VectorXd& pk) {
    if (rows_ == capacity_) grow(2 * capacity_);
    t()[rows_] = tk;
    std::copy_n(qk.data(), d_, q() + rows_ * d_);
    std::copy_n(pk.data(), d_, p() + rows_ * d_);
    if (energy_) H()[rows_] = run.energy(qk, pk);
    ++rows_;
  }
  /// Whether the last row is at time `tk`.
  bool ends_at(double tk) const { return rows_ > 0 && block_[size_t(rows_ - 1)] == tk; }
  RunResult to_python(py::object hits, bool stopped) &&;

 private:
  Eigen::Index d_;
  bool energy_;
  long rows_ = 0, capacity_ = 0;
  std::unique_ptr<double[]> block_;

  double* t() const { return block_.get(); }
  double* q() const { return t() + capacity_; }
  double* p() const { return q() + capacity_ * d_; }
  double* H() const { return p() + capacity_ * d_; }
  // A block of `capacity` rows with the rows so far.
  void grow(long capacity) {
    Output bigger(*this, capacity);
    std::copy_n(t(), rows_, bigger.t());
    std::copy_n(q(), rows_ * d_, bigger.q());
    std::copy_n(p(), rows_ * d_, bigger.p());
    if (energy_) std::copy_n(H(), rows_, bigger.H());
    *this = std::move(bigger);
  }
  Output(const Output& o, long capacity)
      : d_(o.d_),
        energy_(o.energy_),
        rows_(o.rows_),
        capacity_(capacity),
        block_(std::make_unique_for_overwrite<double[]>(size_t(capacity) *
                                                        size_t(1 + 2 * d_ + (energy_ ? 1 : 0)))) {}
};

// The result of the run with `hits` and `stopped`: arrays on the block, which one capsule owns.
RunResult Output::to_python(py::object hits, bool stopped) && {
  double *const t_k = t(), *const q_k = q(), *const p_k = p(), *const H_k = H();
  const py::capsule base = owning(std::move(block_));
  const auto n = py::ssize_t(rows_);
  return {array_on(t_k, n, -1, base),
          array_on(q_k, n, d_, base),
          array_on(p_k, n, d_, base),
          energy_ ? array_on(H_k, n, -1, base) : py::none(),
          std::move(hits),
          stopped};
}

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// t_eval's times (converted to a C-order float64 array held in `keep` if need be); none for None
// (without making an empty array: ~3k instructions, 6 % of a 1-step erkn.solve).
Eigen::Map<const Eigen::VectorXd> output_times(const py::object& t_eval, py::object& keep) {
  if (t_eval.is_none()) return {nullptr, 0};
  using Times = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Times times = Times::ensure(t_eval);
  if (!times || times.ndim() != 1) throw Error("t_eval must be a 1-D array of times");
  keep = times;
  return {times.data(), times.size()};
}

class PyIntegrator {
 public:
  PyIntegrator(const std::string& method, const PySystem& system, double h, const VectorArg& q0,
               const VectorArg& p0, double t0, const Options& options)
      : PyIntegrator(Method::by_name(method), system, h, q0, p0, t0, options) {}
  PyIntegrator(const Method& method, const PySystem& system, double h, const VectorArg& q0,
               const VectorArg& p0, double t0, const Options& options)
      : calls_python_(system.calls_python),
        step_work_(double(q0.size()) * double(method.stages())),
        run_(method, System(system.system), h, q0, p0, options, t0, system.compiled) {}

  void step(long n) {
    if (n < 0) throw Error("step(n): n must be >= 0; got " + std::to_string(n));
    LongRun(py::none()).steps(run_, n, [&](long k) {
      stepping(releases_gil(double(k)), [&] { run_.step(k); });
    });
  }

  // H(q_k, p_k) of each row (n, d) of q and p: the energies of a run's output, on demand.
  py::object energies(const Eigen::Ref<const RowMatrix>& q, const Eigen::Ref<const RowMatrix>& p) {
    if (!run_.system().potential) return py::none();
    if (q.rows() != p.rows() || q.cols() != p.cols() || q.cols() != run_.q().size())
      throw Error("energies: q and p must be (n, d) arrays of the run's dimension");
    std::vector<double> H;
    for (Eigen::Index k = 0; k < q.rows(); ++k)
      H.push_back(run_.energy(q.row(k).transpose(), p.row(k).transpose()));
    const auto [heap, base] = owned(std::move(H));
    return array_on(heap->data(), py::ssize_t(q.rows()), -1, base);
  }
  /// Energies may wait until asked for: U is C++ (a built-in), so computing them later cannot
  /// fail where the run did not.
  bool energy_can_wait() const { return !calls_python_; }

  // Steps to t_end; output at `t_eval` (ascending, in [t, t_end]) or else at the start, every
  // `every`-th step and t_end; with `events` (a sequence of (g, direction, terminal)), their zeros.
  // Ctrl-C and progress(t) between chunks (long_run.hpp).
  RunResult run(double t_end, const py::object& t_eval, long every, bool energy,
                const py::object& events, const py::object& progress) {
    partial_.reset();  // (an earlier failure's output is not this run's)
    py::object keep;   // (t_eval converted, if it had to be)
    const Eigen::Map<const Eigen::VectorXd> times = output_times(t_eval, keep);
    const double steps = steps_to(t_end);
    const bool release = releases_gil(steps);  // (for every chunk: decided once per run)
    Output out(run_.q().size(), energy && bool(run_.system().potential),
               expected_rows(steps, t_eval.is_none() ? -1 : times.size(), every));
    const auto add = [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
      out.add(run_, t, q, p);
    };
    if (!t_eval.is_none())  // (all of them before any step: the chunks see only their own)
      TimeGrid(run_.t(), run_.h()).require_output_times(t_end, times);
    // (on the heap: an std::optional<Events> in this frame was zeroed, 552 bytes, on every run)
    std::unique_ptr<Events> found;
    if (!events.is_none()) found = std::make_unique<Events>(run_, events_from_python(events));
    bool stopped = false;
    try {
      if (t_eval.is_none()) add(run_.t(), run_.q(), run_.p());
      Eigen::Index next = 0;  // the first output time after the last chunk
      const auto chunk = [&](double t_c, long every_c) {
        if (t_eval.is_none()) return chunk_every(found, t_c, add, every_c, release);
        const Eigen::Index from = next;
        while (next < times.size() && (t_c == t_end || times[next] <= t_c)) ++next;
        return chunk_times(found, t_c, times.segment(from, next - from), add, release);
      };
      stopped = LongRun(progress).to(run_, t_end, t_eval.is_none() ? every : 1, chunk);
    } catch (const py::error_already_set& e) {  // (Ctrl-C: the last state joins the output,
      // after the t_eval times reached so far when there are output times)
      if (e.matches(PyExc_KeyboardInterrupt) && !out.ends_at(run_.t()))
        add(run_.t(), run_.q(), run_.p());
      partial_ = result(out, found, events, false);
      throw;
    } catch (...) {  // (a failed run keeps what it computed: erkn.solve attaches it)
      partial_ = result(out, found, events, false);
      throw;
    }
    return result(out, found, events, stopped);
  }

  // Python observer(t, q, p) with copies of the state (the loop holds the GIL), after every
  // `every`-th step and at t_end, or at `times` (between grid points: state_at).
  void integrate(double t_end, const py::object& observer, long every, const py::object& times) {
    if (observer.is_none()) {
      if (!times.is_none()) throw Error("integrate: times need an observer");
      return step_to(t_end, every);
    }
    const auto call = [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
      observer(t, Eigen::VectorXd(q), Eigen::VectorXd(p));
    };
    if (times.is_none()) return run_.integrate(t_end, call, every);
    using Times = py::array_t<double, py::array::c_style | py::array::forcecast>;
    const Times at = Times::ensure(times);
    if (!at || at.ndim() != 1) throw Error("times must be a 1-D array of times");
    run_.integrate(t_end, Eigen::Map<const Eigen::VectorXd>(at.data(), at.size()), call);
  }

  py::tuple state_at(double t) {
    Eigen::VectorXd q, p;
    run_.state_at(t, q, p);
    return py::make_tuple(q, p);
  }

  py::dict statistics() const { return statistics_dict(run_.statistics()); }

  Integrator& get() { return run_; }
  /// The output of the last run() that failed, up to its last completed step, if one did.
  const std::optional<RunResult>& partial() const { return partial_; }

 private:
  // One chunk of run(): to t_c with output every `every` steps (none for every = 0), or at
  // `times`; true when a terminal event stopped it. Without the GIL if `release`
  // (releases_gil); events hold it.
  template <class Add>
  bool chunk_every(const std::unique_ptr<Events>& found, double t_c, Add& add, long every,
                   bool release) {
    const auto none = [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {};
    if (found)
      return every ? found->integrate(run_, t_c, add, every)
                   : found->integrate(run_, t_c, none, kNever);
    stepping(release, [&] { every ? run_.integrate(t_c, add, every) : run_.integrate(t_c); });
    return false;
  }
  // (An observer interval no chunk reaches: none is called.)
  static constexpr long kNever = std::numeric_limits<long>::max();
  template <class Add>
  bool chunk_times(const std::unique_ptr<Events>& found, double t_c,
                   const Eigen::Ref<const Eigen::VectorXd>& times, Add& add, bool release) {
    if (found) return found->integrate(run_, t_c, times, add);
    stepping(release, [&] { run_.integrate(t_c, times, add); });
    return false;
  }

  // About the output's rows: `times` (>= 0: output times), or the start, every `every`-th step
  // and t_end, about `steps` steps away (steps_to); at most a first chunk's steps (long_run.hpp):
  // a run that will be interrupted does not reserve them all.
  long expected_rows(double steps, Eigen::Index times, long every) const {
    const double rows = times >= 0 ? double(times) : 2 + steps / double(every);
    return rows >= 0 ? long(std::min(rows, double(LongRun::kFirstChunk))) : 2;  // (NaN: 2)
  }

  RunResult result(Output& out, const std::unique_ptr<Events>& found, const py::object& events,
                   bool stopped) {
    py::object hits = py::none();
    if (found) hits = hits_to_python(*found, py::len(events), run_.q().size());
    return std::move(out).to_python(std::move(hits), stopped);
  }

  // To t_end without output, in chunks (Ctrl-C between them).
  void step_to(double t_end, long every) {
    if (every < 1)
      throw Error("the observer interval must be >= 1 step; got " + std::to_string(every));
    const bool release = releases_gil(steps_to(t_end));
    LongRun(py::none()).to(run_, t_end, 1, [&](double t_c, long) {
      stepping(release, [&] { run_.integrate(t_c); });
      return false;
    });
  }

  // Whether a run of about `steps` steps goes without the GIL: not if a callback is Python code,
  // nor below kHoldGil steps x dimension x stages. Releasing and retaking it costs ~300
  // instructions, ~70 ns (callgrind; perf, a 1-step Duffing Strang erkn.solve: 1.11 -> 1.05 us),
  // while such a run holds it for some microseconds (Duffing Strang: 15 ns a step).
  bool releases_gil(double steps) const { return !calls_python_ && steps * step_work_ >= kHoldGil; }
  static constexpr double kHoldGil = 1024;
  // Runs f, without the GIL if `release`.
  template <class F>
  static void stepping(bool release, F&& f) {
    if (!release) return f();
    py::gil_scoped_release unlocked;
    f();
  }
  // About the steps to t_c ((t_c - t) / h: an estimate, which cannot fail, unlike the plan).
  double steps_to(double t_c) const { return (t_c - run_.t()) / run_.h(); }

  bool calls_python_;
  double step_work_;  // dimension x stages (stepping)
  Integrator run_;
  std::optional<RunResult> partial_;
};

// The arguments erkn.solve's common call reads, beyond M and grad (positional).
enum Slot { kQ0, kP0, kSpan, kH, kMethod, kEvery, kSlots };
constexpr const char* kSlotNames[kSlots] = {"q0", "p0", "t_span", "h", "method", "every"};

// A Solution's fields (its __slots__ but __dict__ and __weakref__), which make_solution sets.
enum Field {
  kT,
  kQ,
  kP,
  kName,
  kChoice,
  kStatus,
  kTEvents,
  kQEvents,
  kPEvents,
  kYEvents,
  kEnergy,
  kRun,
  kStats,
  kFields
};
constexpr const char* kFieldNames[kFields] = {
    "t",        "q",        "p",        "method",  "choice", "status", "t_events",
    "q_events", "p_events", "y_events", "_energy", "_run",   "_stats"};

// What erkn.solve (the entry, solve_entry) knows of the Python solve: its keyword parameters
// (the names interned in its code object), each with the slot it fills or kSlots (one the
// common call needs to be None), read when the entry is made; and what it takes from erkn's
// namespace.
struct SolveEntry {
  py::dict globals;                                  // erkn's namespace
  py::object checked_name;                           // "_solve_checked": looked up at each call
  py::object solution, later, fallback;              // Solution, _LATER, _attach_partial
  py::object default_method;                         // _DEFAULT_METHOD
  py::tuple names;                                   // the Python solve's co_varnames
  std::vector<std::pair<PyObject*, int>> keywords;   // (a name in `names`, its slot)
  std::array<Py_ssize_t, kFields> offsets;           // the fields' slots in a Solution
  py::object add_events;                             // "_add_events", interned
  py::object zero = py::int_(0), one = py::int_(1);  // Solution.status
  // (keyword_slots' cache: the last kwnames tuple and its names' slots)
  mutable std::pair<py::object, std::vector<int>> last_keywords;
  // The function's name, flags and doc (its text signature and docstring), which CPython reads
  // from here for as long as the function lives: each entry's own.
  std::string doc;
  PyMethodDef def{};
};
// The newest entry's state, which every entry and the other calls into C++ from erkn's Python
// code (_construct_and_run, _partial_solution) take: a reload of erkn runs its __init__ again in
// the same namespace and makes a new entry, and erkn.solve as the user held it before then
// solves into the new Solution class, as the checked path does. (Made by _erkn._solve_entry at
// each import or reload of erkn; never destroyed: it holds Python objects, and a call may be in
// an older one's entry when a gradient reloads erkn.)
SolveEntry* solve_entry_state = nullptr;
const SolveEntry& solve_entry_made() {
  if (!solve_entry_state) throw Error("erkn.solve's entry is made when erkn is imported");
  return *solve_entry_state;
}

// An erkn.Solution (its class: python/erkn/__init__.py) of the integrator `run` (run_capsule's),
// `method` its name, from a run()'s result `out`: made here rather than by a Python __init__
// (~2.1k instructions of a 1-step solve's ~17k), each field stored in its slot (PyObject_SetAttr
// cost ~140 instructions a field, ~840 of a 1-step solve's ~13k; callgrind): t, q, p, method,
// choice, status (1: a terminal event stopped the run), _energy (out's energies, or _LATER if
// `later`: computed on first access), _run; the events None, then set by Solution._add_events
// if there are any; _stats None (read from the run on first access).
py::object make_solution(const SolveEntry& e, py::handle run, py::handle method,
                         const RunResult& out, bool later, py::handle choice) {
  auto* const type = reinterpret_cast<PyTypeObject*>(e.solution.ptr());
  static auto* const no_arguments = new py::tuple();  // (never destroyed, as on_terminal's)
  const auto s =
      py::reinterpret_steal<py::object>(type->tp_new(type, no_arguments->ptr(), nullptr));
  if (!s) throw py::error_already_set();
  const auto set = [&](Field field, py::handle value) {  // (the slots start empty: NULL)
    *reinterpret_cast<PyObject**>(reinterpret_cast<char*>(s.ptr()) + e.offsets[field]) =
        value.inc_ref().ptr();
  };
  set(kT, out.t), set(kQ, out.q), set(kP, out.p), set(kName, method), set(kChoice, choice);
  set(kStatus, out.stopped ? e.one.ptr() : e.zero.ptr());
  for (Field f : {kTEvents, kQEvents, kPEvents, kYEvents, kStats}) set(f, Py_None);
  set(kEnergy, later ? e.later.ptr() : out.energy.ptr()), set(kRun, run);
  if (!out.hits.is_none()) s.attr(e.add_events)(out.hits);
  return s;
}

// A registry method's name as a Python str, kept for the last method asked (solve's loops: one
// method; the registry's entries stay where they are).
py::handle name_of(const Method& method) {
  static auto* const last = new std::pair<const Method*, py::object>(nullptr, py::none());
  if (last->first != &method)
    *last = {&method, py::str(method.name().data(), method.name().size())};
  return last->second;
}

// A Solution's integrator (its _run): a capsule of that name owning a PyIntegrator, rather than a
// pybind11 instance of _Integrator (~1.6k instructions to make and free: the instance registry,
// type lookups by name hash).
constexpr const char* kRunCapsule = "erkn.solve's integrator";
py::object run_capsule(std::unique_ptr<PyIntegrator> run) {
  PyObject* const capsule = PyCapsule_New(run.get(), kRunCapsule, [](PyObject* c) {
    delete static_cast<PyIntegrator*>(PyCapsule_GetPointer(c, kRunCapsule));
  });
  if (!capsule) throw py::error_already_set();
  run.release();
  return py::reinterpret_steal<py::object>(capsule);
}
PyIntegrator& run_of(py::handle capsule) {
  auto* const run = static_cast<PyIntegrator*>(PyCapsule_GetPointer(capsule.ptr(), kRunCapsule));
  if (!run) throw py::error_already_set();
  return *run;
}

// erkn.solve's construction and run() in one call, returning the Solution: each call through
// pybind11 costs ~1.5k instructions (argument and self casts, type lookups), and solve made four
// (the constructor, _run, _energy_can_wait, method) of a 1-step solve's ~56k (callgrind, Duffing,
// Strang). The integrator (run_capsule) is put in `held` before it runs, so that a failed run's
// output stays reachable (partial_solution). With `energy`, the energies are computed now only if
// they cannot wait (Python callbacks). `method`: the registry's; `choice`: Solution.choice (None
// without tol).
py::object construct_and_run(py::object& held, const Method& method, const PySystem& system,
                             double h, const VectorArg& q0, const VectorArg& p0, double t0,
                             const Options& options, double t_end, const py::object& t_eval,
                             long every, bool energy, const py::object& events,
                             const py::object& progress, const py::object& choice) {
  auto owned = std::make_unique<PyIntegrator>(method, system, h, q0, p0, t0, options);
  PyIntegrator& run = *owned;
  held = run_capsule(std::move(owned));
  const bool later = energy && run.energy_can_wait();
  const RunResult out = run.run(t_end, t_eval, every, energy && !later, events, progress);
  return make_solution(solve_entry_made(), held, name_of(method), out, later, choice);
}

// The Solution of a failed run (`capsule`: its integrator) up to its last completed step, or None
// if it failed before its run began.
py::object partial_solution(py::handle capsule, py::handle choice) {
  PyIntegrator& run = run_of(capsule);
  const std::optional<RunResult>& partial = run.partial();
  if (!partial) return py::none();
  const std::string_view name = run.get().method().name();
  // (its energies None: left for later, or no U)
  return make_solution(solve_entry_made(), capsule, py::str(name.data(), name.size()), *partial,
                       partial->energy.is_none(), choice);
}

// x's value if it is a Python float or int (not a bool; not an int beyond a double's range).
std::optional<double> plain_number(py::handle x) {
  if (PyFloat_CheckExact(x.ptr())) return PyFloat_AS_DOUBLE(x.ptr());
  if (!PyLong_CheckExact(x.ptr())) return std::nullopt;
  const double value = PyLong_AsDouble(x.ptr());
  if (value == -1.0 && PyErr_Occurred()) return PyErr_Clear(), std::nullopt;
  return value;
}

// x's entries if it is a NumPy array of NumPy's own float64 dtype (native byte order), 1-D and
// contiguous: what erkn.solve's _state passes on as it is.
std::optional<Eigen::Map<const Eigen::VectorXd>> plain_vector(py::handle x) {
  auto& api = py::detail::npy_api::get();
  static PyObject* const float64 = api.PyArray_DescrFromType_(py::detail::npy_api::NPY_DOUBLE_);
  if (Py_TYPE(x.ptr()) != api.PyArray_Type_) return std::nullopt;
  const auto* a = py::detail::array_proxy(x.ptr());
  if (a->nd != 1 || a->descr != float64 || (a->dimensions[0] > 1 && a->strides[0] != 8))
    return std::nullopt;
  return Eigen::Map<const Eigen::VectorXd>(reinterpret_cast<const double*>(a->data),
                                           a->dimensions[0]);
}

// x's value if it is a Python int in [1, 2^53] (erkn.solve's `every`).
std::optional<long> plain_interval(py::handle x) {
  if (!PyLong_CheckExact(x.ptr())) return std::nullopt;
  int overflow = 0;
  const long long n = PyLong_AsLongLongAndOverflow(x.ptr(), &overflow);
  if (overflow || n < 1 || n > (1LL << 53)) return std::nullopt;
  return long(n);
}

// x as UTF-8 if it is a Python str.
std::optional<std::string_view> plain_name(py::handle x) {
  if (!PyUnicode_CheckExact(x.ptr())) return std::nullopt;
  Py_ssize_t size = 0;
  const char* text = PyUnicode_AsUTF8AndSize(x.ptr(), &size);
  if (!text) return PyErr_Clear(), std::nullopt;
  return std::string_view(text, size_t(size));
}

// sys.stderr.isatty(), asked once per stderr object (a system call of ~5 us here). sys.stderr is
// read from sys's namespace dict with an interned key (sys.stderr as an attribute lookup:
// ~240 instructions).
bool on_terminal() {
  // (never destroyed: they hold Python objects, which must not be released after the
  // interpreter has ended)
  static auto* const last = new std::pair<py::object, bool>(py::none(), false);
  static auto* const sys = new py::dict(py::module_::import("sys").attr("__dict__"));
  static auto* const name =
      new py::object(py::reinterpret_steal<py::object>(PyUnicode_InternFromString("stderr")));
  PyObject* const stderr_now = PyDict_GetItemWithError(sys->ptr(), name->ptr());  // (borrowed)
  if (!stderr_now) {
    if (PyErr_Occurred()) throw py::error_already_set();
    throw py::attribute_error("module 'sys' has no attribute 'stderr'");  // (as sys.stderr)
  }
  if (last->first.ptr() != stderr_now) {
    const py::object now = py::reinterpret_borrow<py::object>(stderr_now);
    *last = {now, py::bool_(now.attr("isatty")()).cast<bool>()};
  }
  return last->second;
}

// The slot of each name in `kwnames` (a vectorcall's keyword names): -1 if it is not a keyword of
// solve's by identity (an unknown name, or one not interned), kSlots for one the common call needs
// to be None. Kept for the last tuple asked: a call site passes the same one (its code's
// constant) on every call, and searching solve's keywords for each name mispredicted (perf: ~30 %
// of solve_entry's own time, ~1 % of a 1-step solve).
const std::vector<int>& keyword_slots(const SolveEntry& e, PyObject* kwnames) {
  auto& [last, slots] = e.last_keywords;
  if (last.ptr() != kwnames) {
    slots.clear();
    for (Py_ssize_t k = 0; k < PyTuple_GET_SIZE(kwnames); ++k) {
      PyObject* const name = PyTuple_GET_ITEM(kwnames, k);
      const auto known = std::find_if(e.keywords.begin(), e.keywords.end(),
                                      [&](const auto& kw) { return kw.first == name; });
      slots.push_back(known == e.keywords.end() ? -1 : known->second);
    }
    last = py::reinterpret_borrow<py::object>(kwnames);  // (held: its address stays its own)
  }
  return slots;
}

// The call's keywords in their slots (kwnames: the vectorcall's names, their values after the
// positional ones); false if one is not a keyword of solve's by identity (solve's checked path
// then reports or takes it) or one the common call does not read is not None.
bool fill_slots(const SolveEntry& e, PyObject* const* values, PyObject* kwnames,
                std::array<PyObject*, kSlots>& slots) {
  if (!kwnames) return true;
  const std::vector<int>& known = keyword_slots(e, kwnames);
  for (size_t k = 0; k < known.size(); ++k) {
    if (known[k] < 0) return false;
    if (known[k] < kSlots)
      slots[size_t(known[k])] = values[k];
    else if (values[k] != Py_None)
      return false;
  }
  return true;
}

// Method::by_name(name), kept for the last name asked: a loop of solves asks for one method again
// and again, and by_name compares with the registry's names in turn (~360 instructions for
// Strang, more for later methods). A method found stays the answer for its name: the registry
// only grows (load_methods), and by_name returns the first match.
const Method& method_named(std::string_view name) {
  static auto* const last = new std::pair<std::string, const Method*>("", nullptr);
  if (!last->second || name != last->first) {
    const Method& found = Method::by_name(name);  // (throws for an unknown name: nothing kept)
    *last = {std::string(name), &found};
  }
  return *last->second;
}

// erkn.solve's common call: M a float or an erkn.Stiffness, grad a built-in potential's name,
// q0 and p0 float64 1-D arrays, t_span a tuple or list of two numbers, h a number, method a name
// other than "auto" (or None or absent: the default), every an int in [1, 2^53] (or absent), every
// other argument None or absent, and stderr not a terminal (progress None draws no bar). In these
// forms solve's checked path (_solve_checked's checks and conversions: _span, _state, _real,
// _every, _system's, _progress) leaves each argument as it is, so none is repeated here; every
// value is checked where it is for any call (the System, the method's name, the Integrator).
// Returns the Solution, or None for another form (the checked path's).
py::object solve_builtin(const SolveEntry& e, py::object& held, py::handle M, py::handle grad,
                         const std::array<PyObject*, kSlots>& a) {
  if (!a[kQ0] || !a[kP0] || !a[kSpan] || !a[kH]) return py::none();
  const py::handle t_span = a[kSpan];
  const bool span = (PyTuple_CheckExact(t_span.ptr()) || PyList_CheckExact(t_span.ptr())) &&
                    PySequence_Fast_GET_SIZE(t_span.ptr()) == 2;
  const auto t0 = span ? plain_number(PySequence_Fast_GET_ITEM(t_span.ptr(), 0)) : std::nullopt;
  const auto t1 = span ? plain_number(PySequence_Fast_GET_ITEM(t_span.ptr(), 1)) : std::nullopt;
  const auto step = plain_number(a[kH]);
  const auto q = plain_vector(a[kQ0]), p = plain_vector(a[kP0]);
  const auto name = plain_name(grad);
  const auto method_name =
      plain_name(a[kMethod] && a[kMethod] != Py_None ? a[kMethod] : e.default_method.ptr());
  const auto interval = a[kEvery] ? plain_interval(a[kEvery]) : std::optional<long>(1);
  if (!t0 || !t1 || !step || !q || !p || !name || !method_name || *method_name == "auto" ||
      !interval || !(PyFloat_CheckExact(M.ptr()) || py::isinstance<Stiffness>(M)) || on_terminal())
    return py::none();
  const auto system = builtin_system(M, std::string(*name), {}, q->size());
  return construct_and_run(held, method_named(*method_name), *system, *step, *q, *p, *t0, Options(),
                           *t1, py::none(), *interval, true, py::none(), py::none(), py::none());
}

// With a Python error set and a run `held` (if one was built): the error carries the run's output
// up to its last completed step as its `solution` (solve's _attach_partial, the checked path's
// too, given [held]).
void attach_partial(const SolveEntry& e, const py::object& held) {
  if (!held) return;
  PyObject *type = nullptr, *value = nullptr, *trace = nullptr;
  PyErr_Fetch(&type, &value, &trace);
  PyErr_NormalizeException(&type, &value, &trace);
  if (trace) PyException_SetTraceback(value, trace);
  PyObject* const holder = PyList_New(1);
  PyObject* done = nullptr;
  if (holder) {
    PyList_SET_ITEM(holder, 0, held.inc_ref().ptr());
    PyObject* args[] = {holder, Py_None, value};
    done = PyObject_Vectorcall(e.fallback.ptr(), args, 3, nullptr);
    Py_DECREF(holder);
  }
  if (done)
    Py_DECREF(done);
  else
    PyErr_Clear();  // (the run's own error is the one to report)
  PyErr_Restore(type, value, trace);
}

// erkn.solve as CPython calls it (vectorcall, without pybind11's dispatch: ~1.3k instructions a
// call) and without the Python solve's frame (binding 20 keyword parameters, ~130 ns): the
// common call (solve_builtin) here; any other form, or a keyword not matched by identity, goes
// to the Python solve's checked path (erkn._solve_checked, looked up at each such call) with its
// arguments as given, which then binds, checks and reports them (the same errors). C++
// exceptions reach Python through pybind11's own translators, tried as its dispatcher tries them
// (module-local ones first): erkn::Error as erkn.Error.
PyObject* solve_entry(PyObject*, PyObject* const* args, size_t nargsf, PyObject* kwnames) {
  const SolveEntry& e = *solve_entry_state;  // (the newest: made with the function itself)
  const Py_ssize_t n = PyVectorcall_NARGS(nargsf);
  py::object held;  // (the integrator, once built)
  try {
    std::array<PyObject*, kSlots> slots{};
    if (n == 2 && fill_slots(e, args + n, kwnames, slots)) {
      py::object out = solve_builtin(e, held, args[0], args[1], slots);
      if (!out.is_none()) return out.release().ptr();
    }
    return PyObject_Vectorcall(e.globals[e.checked_name].ptr(), args, nargsf, kwnames);
  } catch (py::error_already_set& err) {
    err.restore();
  } catch (...) {
    namespace detail = py::detail;
    if (!detail::apply_exception_translators(
            detail::get_local_internals().registered_exception_translators) &&
        !detail::apply_exception_translators(
            detail::get_internals().registered_exception_translators))
      PyErr_SetString(PyExc_SystemError, "erkn.solve: an exception no translator took");
  }
  attach_partial(e, held);
  return nullptr;
}

// The offset in an instance of `cls` of its slot `name` (from its member descriptor).
Py_ssize_t slot_offset(const py::object& cls, const char* name) {
  const py::object d = cls.attr("__dict__").attr("get")(name);
  if (Py_TYPE(d.ptr()) != &PyMemberDescr_Type ||
      reinterpret_cast<PyMemberDescrObject*>(d.ptr())->d_member->type != T_OBJECT_EX)
    throw Error(std::string("erkn.Solution has no slot ") + name);
  return reinterpret_cast<PyMemberDescrObject*>(d.ptr())->d_member->offset;
}

// _erkn._solve_entry(checked, namespace, doc): erkn.solve, the entry (solve_entry) before the
// Python solve `checked` (its keyword parameters read from its code object), with `doc` (its
// text signature and docstring); `namespace`: erkn's, where it finds _solve_checked, Solution,
// _LATER, _attach_partial and _DEFAULT_METHOD.
py::object make_solve_entry(const py::function& checked, const py::dict& globals,
                            const std::string& doc) {
  auto* e =
      new SolveEntry{globals,
                     py::str("_solve_checked"),
                     globals["Solution"],
                     globals["_LATER"],
                     globals["_attach_partial"],
                     globals["_DEFAULT_METHOD"],
                     checked.attr("__code__").attr("co_varnames"),
                     {},
                     {},
                     py::reinterpret_steal<py::object>(PyUnicode_InternFromString("_add_events"))};
  for (size_t k = 0; k < e->offsets.size(); ++k)
    e->offsets[k] = slot_offset(e->solution, kFieldNames[k]);
  e->doc = doc;
  const py::object code = checked.attr("__code__");
  const auto positional = code.attr("co_argcount").cast<Py_ssize_t>();
  const auto keywords = code.attr("co_kwonlyargcount").cast<Py_ssize_t>();
  const py::tuple& names = e->names;
  for (Py_ssize_t k = positional; k < positional + keywords; ++k) {
    const std::string name = py::str(names[size_t(k)]);
    const auto slot = std::find(std::begin(kSlotNames), std::end(kSlotNames), name);
    e->keywords.emplace_back(names[size_t(k)].ptr(), int(slot - std::begin(kSlotNames)));
  }
  e->def = {"solve", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&solve_entry)),
            METH_FASTCALL | METH_KEYWORDS, e->doc.c_str()};
  auto function = py::reinterpret_steal<py::object>(
      PyCFunction_NewEx(&e->def, nullptr, py::str(globals["__name__"]).ptr()));
  if (!function) throw py::error_already_set();
  solve_entry_state = e;
  return function;
}

// erkn.Integrator's C++ side.
void bind_integrator_class(py::module_& m) {
  py::class_<PyIntegrator>(m, "_Integrator")
      .def(py::init<const std::string&, const PySystem&, double, const VectorArg&, const VectorArg&,
                    double, const Options&>(),
           py::arg("method"), py::arg("system"), py::arg("h"), py::arg("q0"), py::arg("p0"),
           py::arg("t0"), py::arg("options"))
      .def("step", &PyIntegrator::step, py::arg("n") = 1, "n steps of size h")
      .def("integrate", &PyIntegrator::integrate, py::arg("t_end"),
           py::arg("observer") = py::none(), py::arg("every") = 1, py::arg("times") = py::none(),
           "steps to t_end (off the grid: a last shorter step); observer(t, q, p) after every "
           "`every`-th step and at t_end, or at `times` (ascending, in [t, t_end]; between grid "
           "points by state_at, which leaves the trajectory unchanged)")
      .def(
          "_run",
          [](PyIntegrator& r, double t_end, const py::object& t_eval, long every, bool energy,
             const py::object& events, const py::object& progress) {
            return r.run(t_end, t_eval, every, energy, events, progress).as_tuple();
          },
          py::arg("t_end"), py::arg("t_eval"), py::arg("every"), py::arg("energy"),
          py::arg("events") = py::none(), py::arg("progress") = py::none())
      .def("state_at", &PyIntegrator::state_at, py::arg("t"),
           "(q, p) at t in [t, t + h] by a step of size t - self.t; the integrator is unchanged")
      .def(
          "set_state",
          [](PyIntegrator& r, const VectorArg& q, const VectorArg& p, double t) {
            r.get().set_state(q, p, t);
          },
          py::arg("q"), py::arg("p"), py::arg("t"))
      .def(
          "set_step_size", [](PyIntegrator& r, double h) { r.get().set_step_size(h); },
          py::arg("h"))
      .def("steps_until", [](PyIntegrator& r, double t) { return r.get().steps_until(t); })
      .def(
          "energy", [](PyIntegrator& r) { return r.get().energy(); },
          "H(q, p) at the current state")
      .def_property_readonly(
          "q", [](PyIntegrator& r) { return Eigen::VectorXd(r.get().q()); }, "a copy of q")
      .def_property_readonly(
          "p", [](PyIntegrator& r) { return Eigen::VectorXd(r.get().p()); }, "a copy of p")
      .def_property_readonly("t", [](PyIntegrator& r) { return r.get().t(); })
      .def_property_readonly("h", [](PyIntegrator& r) { return r.get().h(); })
      .def_property_readonly("method",
                             [](PyIntegrator& r) { return std::string(r.get().method().name()); })
      .def_property_readonly("statistics", &PyIntegrator::statistics,
                             "counters and wall_time, cpu_time (seconds in integrate and step)")
      .def_property_readonly(
          "_options", [](PyIntegrator& r) { return r.get().options(); }, "a copy")
      .def_property_readonly("_partial",
                             [](PyIntegrator& r) {
                               const auto& partial = r.partial();
                               return partial ? py::object(partial->as_tuple()) : py::none();
                             })
      .def("_energies", &PyIntegrator::energies, py::arg("q"), py::arg("p"));
}

// erkn.solve's calls into C++: the entry (_solve_entry, made by erkn's __init__ at each import or
// reload), the checked path's construction and run in one (_construct_and_run), and whether stderr
// is a terminal (_on_terminal).
void bind_solve_calls(py::module_& m) {
  m.def("_solve_entry", &make_solve_entry, py::arg("checked"), py::arg("namespace"),
        py::arg("doc"));
  m.def(
      "_construct_and_run",
      [](py::list holder, const std::string& method, const PySystem& system, double h,
         const VectorArg& q0, const VectorArg& p0, double t0, const Options& options, double t_end,
         const py::object& t_eval, long every, bool energy, const py::object& events,
         const py::object& progress, const py::object& choice) {
        py::object held;
        try {
          return construct_and_run(held, Method::by_name(method), system, h, q0, p0, t0, options,
                                   t_end, t_eval, every, energy, events, progress, choice);
        } catch (...) {  // (a failed run: its integrator joins `holder`, for _attach_partial)
          if (held) holder.append(held);
          throw;
        }
      },
      py::arg("holder"), py::arg("method"), py::arg("system"), py::arg("h"), py::arg("q0"),
      py::arg("p0"), py::arg("t0"), py::arg("options"), py::arg("t_end"), py::arg("t_eval"),
      py::arg("every"), py::arg("energy"), py::arg("events"), py::arg("progress"),
      py::arg("choice"));
  m.def("_partial_solution", &partial_solution, py::arg("run"), py::arg("choice"));
  m.def(
      "_run_statistics", [](py::handle run) { return run_of(run).statistics(); }, py::arg("run"));
  m.def(
      "_run_energies",
      [](py::handle run, const Eigen::Ref<const RowMatrix>& q,
         const Eigen::Ref<const RowMatrix>& p) { return run_of(run).energies(q, p); },
      py::arg("run"), py::arg("q"), py::arg("p"));
  m.def("_on_terminal", &on_terminal);
}

}  // namespace

void bind_integrator(py::module_& m) {
  bind_integrator_class(m);
  bind_solve_calls(m);
}

}  // namespace erkn::python
