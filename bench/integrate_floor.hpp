// erkn_integrate_benchmark's implicit floor (issue 17, target 4): whether an implicit cell's miss
// is erkn's or the method's work through an opaque callback, measured in the cell's own rounds.
// In the implicit group of a scene with scalar or diagonal M at D = 1, 2 (Duffing, stellar
// orbits), per implicit method the loop a specialist writes for it (bench/implicit_floor.hpp,
// run through bench/implicit_floor_runs.hpp's FloorRuns: construct + run, its set-up, the
// coefficients read through erkn::Method::evaluate, counted as its construction as erkn's is)
// through the same System::gradient as it is and with the next step's first Q_0 formed at the end
// of a step (carry), the same two with the gradient inlined, and erkn's explicit methods with
// that gradient compiled in (erkn::make_integrator): the inlined floor's reference.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <erkn/erkn.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "implicit_floor_runs.hpp"
#include "integrate_timing.hpp"

namespace bench {

/// What the floor says of one implicit cell: ratios of CPU per grad U, medians over rounds.
struct FloorColumns {
  enum class Status { not_timed, disagrees, timed };
  Status status = Status::not_timed;
  double diff = NAN;        // the variants' largest final-state difference to erkn's (relative)
  double floor = NAN;       // floor through System::gradient (per round the faster of its
                            // variants) / the explicit path
  double erkn_floor = NAN;  // erkn / that floor
  double inlined = NAN;     // floor inlined (the faster variant) / explicit path compiled in
};

/// The floor's share of a scene's implicit group: contenders appended after erkn's runs of every
/// registry method, and their columns once the group has run.
class FloorGroup {
 public:
  virtual ~FloorGroup() = default;
  /// Appends, per implicit method of `methods` whose floor agrees with erkn (checked here, before
  /// timing), its floor's contenders; then the explicit methods' runs with the gradient compiled
  /// in. `runs` holds erkn's contenders, one per method, on entry.
  virtual void add(const std::vector<erkn::Method>& methods, Schedule::Contenders& runs) = 0;
  /// The columns of the k-th implicit method of `methods` from the group's seconds t (per
  /// contender and round), erkn's seconds per grad U of it per round and the explicit path's.
  virtual FloorColumns columns(size_t k, const Schedule::Seconds& t,
                               const std::vector<double>& erkn_grad,
                               const std::vector<double>& explicit_grad) const = 0;
};

/// FloorGroup on a scene of dimension D with the peer's gradient functor Gradient.
template <int D, class Gradient>
class FloorGroupOf final : public FloorGroup {
 public:
  FloorGroupOf(const floor::FloorScene& s, Gradient g)
      : sc_(std::make_shared<Runs>(Runs{s, g, floor::Settings{}})) {
    if (s.problem.dim() != D) throw std::invalid_argument("FloorGroupOf: dimension is not D");
  }

  void add(const std::vector<erkn::Method>& methods, Schedule::Contenders& runs) override {
    evaluations_.assign(runs.size(), NAN);  // (erkn's: not the floor's to read)
    for (const erkn::Method& m : methods)
      if (!m.is_explicit()) add_method(m, runs);
    compiled_from_ = runs.size();
    for (const erkn::Method& m : methods)
      if (m.is_explicit() && !m.has_modified_kicks() && !m.is_processed()) {
        evaluations_.push_back(double(sc_->erkn_compiled(m)));
        runs.push_back([sc = sc_, m] { sc->erkn_compiled(m); });
      }
  }

  FloorColumns columns(size_t k, const Schedule::Seconds& t, const std::vector<double>& erkn_grad,
                       const std::vector<double>& explicit_grad) const override {
    const Entry& e = entries_.at(k);
    FloorColumns c;
    c.diff = e.diff;
    c.status = e.first ? FloorColumns::Status::timed : FloorColumns::Status::disagrees;
    if (!e.first) return c;
    const std::vector<double> cb = faster(t, *e.first), inl = faster(t, *e.first + 2);
    c.floor = median_ratio(cb, explicit_grad), c.erkn_floor = median_ratio(erkn_grad, cb);
    c.inlined = median_ratio(
        inl,
        per_grad_median(t, evaluations_, contender_range(compiled_from_, evaluations_.size())));
    return c;
  }

 private:
  using Runs = floor::FloorRuns<D, Gradient>;
  static constexpr floor::Variant kVariants[2] = {floor::Variant::plain, floor::Variant::carry};
  /// An implicit method's floor: the largest difference of its variants' final states to erkn's
  /// (relative), and where it agrees the index of its first contender: through System::gradient
  /// plain, carry, then inlined plain, carry.
  struct Entry {
    double diff = 0;
    std::optional<size_t> first;
  };

  /// One run of m's floor loop (variant v; gradient inlined or through System::gradient): its
  /// gradient evaluations, final state in q, p.
  static long run(Runs& sc, const erkn::Method& m, floor::Variant v, bool inlined,
                  Eigen::VectorXd* q = nullptr, Eigen::VectorXd* p = nullptr) {
    return inlined ? sc.floor(m, sc.g, v, q, p) : sc.floor(m, sc.callback(), v, q, p);
  }

  /// m's variants run once against erkn's final state; their contenders if all agree.
  void add_method(const erkn::Method& m, Schedule::Contenders& runs) {
    Eigen::VectorXd qe, pe, q, p;
    sc_->erkn(m, &qe, &pe);
    Entry e;
    std::vector<double> evaluations;
    for (bool inlined : {false, true})
      for (floor::Variant v : kVariants) {
        double d = std::numeric_limits<double>::infinity();
        try {
          evaluations.push_back(double(run(*sc_, m, v, inlined, &q, &p)));
          d = floor::relative_diff(qe, pe, q, p);
        } catch (const std::runtime_error&) {  // (a stage that fails: the floor disagrees)
        }
        e.diff = std::isnan(d) ? d : std::max(e.diff, d);
      }
    if (e.diff <= floor::kAgree) {
      e.first = runs.size();
      evaluations_.insert(evaluations_.end(), evaluations.begin(), evaluations.end());
      for (bool inlined : {false, true})
        for (floor::Variant v : kVariants)
          runs.push_back([sc = sc_, m, v, inlined] { run(*sc, m, v, inlined); });
    }
    entries_.push_back(e);
  }

  /// Per round the faster of contenders `from` (plain) and from + 1 (carry), seconds per grad U:
  /// the variant a specialist would pick.
  std::vector<double> faster(const Schedule::Seconds& t, size_t from) const {
    const std::vector<double> plain = floor::per_grad(t, evaluations_, from),
                              carry = floor::per_grad(t, evaluations_, from + 1);
    std::vector<double> out(plain.size());
    for (size_t r = 0; r < out.size(); ++r) out[r] = std::min(plain[r], carry[r]);
    return out;
  }

  std::shared_ptr<Runs> sc_;
  std::vector<Entry> entries_;       // per implicit method, in registry order
  std::vector<double> evaluations_;  // per contender of the group (NaN: erkn's)
  size_t compiled_from_ = 0;         // the first explicit run with the gradient compiled in
};

}  // namespace bench
