// The method registry: every method the generator emitted, by id or by the paper's name, and the
// methods a program adds: tables erkn-generate emitted for a user's spec (erkn_add_methods in
// CMake, compiled into the program, added at its start) and method files (Method::load).
// erkn's own list comes from generated/include/erkn/generated/methods.def; nothing here is
// per-method.
#pragma once

#include <array>
#include <deque>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "erkn/generated/tables.hpp"

namespace erkn {

enum class MethodId {
#define ERKN_METHOD(id, name, stages, order, kind) id,
#include "erkn/generated/methods.def"
#undef ERKN_METHOD
};

enum class Kind { erkn, rkn };

inline constexpr int kMaxStages = generated::kMaxStages;

/// Coefficients of one method at one v = h^2 lambda (scalar). abar(i, j) for j <= i, 0-based.
struct Coefficients {
  /// Position of abar_ij (0 <= j <= i) in the row-packed lower triangle abar_11, abar_21,
  /// abar_22, ...: the order of abar_packed, of Method::evaluate and of the generated tables.
  static constexpr int packed(int i, int j) { return i * (i + 1) / 2 + j; }
  /// The size of that triangle for kMaxStages stages (packed(kMaxStages, 0)): abar_packed's, and
  /// of any array that receives a method's abar (Method::evaluate).
  static constexpr int kMaxPacked = kMaxStages * (kMaxStages + 1) / 2;

  int s = 0;
  std::array<double, kMaxStages> c{}, b{}, bbar{};
  std::array<double, kMaxPacked> abar_packed{};
  double abar(int i, int j) const { return abar_packed[packed(i, j)]; }
};

class Method {
 public:
  /// Throws erkn::Error for an id outside the registry (e.g. a cast integer).
  static const Method& get(MethodId id);
  /// Lookup by the paper's name ("SERKN3s4(1)") or the id ("SERKN3s4_1"); throws erkn::Error
  /// naming the unknown method and listing the known ones.
  static const Method& by_name(std::string_view name);
  /// erkn's own methods (methods.def order), then the added ones in the order they were added.
  /// References stay valid when methods are added.
  static const std::deque<Method>& all();

  /// Adds a method defined outside erkn's tables (the source erkn_add_methods compiles calls it
  /// at program start). `table` and what it points to must outlive the program. Throws
  /// erkn::Error, adding nothing, for a name or id already listed, stages outside 1..kMaxStages,
  /// an implicit table without its coefficient function, a table without its closed forms, or
  /// modified kicks in an implicit table.
  /// Not thread-safe: add methods before other threads look methods up.
  static const Method& add(const generated::Table& table);
  /// Reads a method file written by `erkn-generate --json` (explicit methods: constant
  /// coefficients), checks the orders each method claims against the order conditions
  /// (order_conditions.hpp, long double) and adds the methods. Throws erkn::Error, adding none
  /// of the file's methods, for an unreadable or malformed file, a failing condition (named, with
  /// its residual), modified kicks (their order conditions are the generator's: compile such
  /// methods with erkn_add_methods), a kind other than explicit, or a name already listed.
  static std::vector<Method> load(const std::string& path);

  MethodId id() const { return id_; }
  std::string_view name() const { return table_->name; }
  std::string_view id_name() const { return table_->id; }
  int stages() const { return table_->stages; }
  int order() const { return table_->order; }
  /// How the runtime integrates it: erkn (exact linear flow) or rkn (V -> 0 limit).
  Kind kind() const { return table_->rkn ? Kind::rkn : Kind::erkn; }
  /// abar_ii = 0: every stage is explicit (a splitting method: exact linear flow and kicks).
  bool is_explicit() const { return table_->explicit_method; }
  /// Some stage kicks with grad(|grad U|^2) too (modified kicks, e.g. force-gradient methods
  /// and correctors): the System needs hessian_vector_product or hessian (erkn/system.hpp).
  bool has_modified_kicks() const { return table_->modified != nullptr; }
  /// e_1..e_s: stage i kicks p -= h (d_i grad U + h^2 e_i grad(|grad U|^2)); empty for plain
  /// kicks.
  std::span<const double> modified() const {
    return {table_->modified, has_modified_kicks() ? size_t(stages()) : 0};
  }
  /// psi = pi o K o pi^-1 (erkn/table.hpp, Table::pre_drift): the stepper steps the kernel K
  /// and applies pi^-1 when a state is set, pi to every state it gives out (q(), p(), output
  /// times, observers, energy()); order() is psi's effective order.
  bool is_processed() const { return table_->npre > 0; }
  /// The kernel K's own order (processed methods; else order()).
  int kernel_order() const { return is_processed() ? table_->kernel_order : order(); }
  /// A method of the source paper (Shi, Zhang & Wang) or its V -> 0 limit: the spec's `section`.
  bool from_paper() const { return table_->paper; }
  /// "erkn", "explicit" or "rkn" (the spec's kind; explicit methods are erkn methods).
  std::string_view kind_name() const;
  /// Certified order in h of the eps^K terms (index K-1) for H = A + eps B; empty for RKN
  /// limits.
  std::span<const int> generalized_order() const {
    return {table_->generalized_order, size_t(table_->ngeneralized)};
  }
  /// The generator's leading error constant (table.hpp: the 2-norm of the residuals of the
  /// order conditions of power order() + 1); NaN if none of the conditions checked fails.
  double error_constant() const { return table_->error_constant; }
  /// The same per power of eps (index K-1), at power generalized_order()[K-1] + 1; empty for
  /// RKN limits, NaN entries where no condition checked fails.
  std::span<const double> generalized_error_constant() const {
    return {table_->generalized_error_constant, size_t(table_->ngeneralized)};
  }
  std::string_view reference() const { return table_->reference; }
  int num_coefficients() const { return 2 * stages() + stages() * (stages() + 1) / 2; }

  /// Coefficients at v >= 0; throws erkn::Error for v < 0, non-finite v, v within a relative
  /// pole_tolerance of a pole (the message names the pole), or (methods not entire()) v beyond
  /// kPoleSearchMax.
  Coefficients at(double v, double pole_tolerance = 1e-6) const;
  /// b[s], bbar[s], abar[s(s+1)/2] at v (unchecked: at() checks v): the table's emitted
  /// function, or for an explicit method given as data (Method::load) the explicit family's
  /// closed forms from c and d.
  void evaluate(double v, double* b, double* bbar, double* abar) const;
  /// Taylor coefficient of v^k (k < generated::kSeriesTerms) of coefficient function `index`
  /// (order b_1..b_s, bbar_1..bbar_s, abar_11, abar_21, abar_22, ...).
  double series(int index, int k) const;
  std::span<const double> poles() const { return {table_->poles, size_t(table_->npoles)}; }
  /// Coefficients entire in v (no pole at any v, so any step size is valid): the RKN limits
  /// (constants) and every method whose coefficients have no pole in (0, kPoleSearchMax] (the
  /// explicit and the pole-free ones), whose closed forms are then polynomials in phi-functions
  /// (tests/runtime/large_step_test.cpp certifies that for the registry). Only the other methods
  /// refuse v beyond kPoleSearchMax, where their poles are not known.
  bool entire() const { return kind() == Kind::rkn || poles().empty(); }
  /// The pole nearest to v, or a negative number if the method has none.
  double nearest_pole(double v) const;
  /// The pole p with |v - p| <= tolerance * p, or a negative number if there is none: the one
  /// test behind every refusal of a v (here and in the integrator's step-size check).
  double pole_within(double v, double tolerance) const;
  const generated::Table& table() const { return *table_; }

  Method(MethodId id, const generated::Table* table) : id_(id), table_(table) {}

 private:
  MethodId id_;
  const generated::Table* table_;
};

}  // namespace erkn
