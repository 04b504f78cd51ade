// The generated-table contract: what erkn-generate emits per method (generated/src/tables.cpp)
// and the registry (method.hpp) reads. Hand-written; the emitted data fills it.
#pragma once

namespace erkn::generated {

/// One method (or the V -> 0 limit of one). Coefficient functions are listed in the order
/// b_1..b_s, bbar_1..bbar_s, abar_11, abar_21, abar_22, abar_31, ... (lower triangle, row-major).
struct Table {
  const char* name;  ///< e.g. "SERKN3s4(1)"
  const char* id;    ///< C identifier, e.g. "SERKN3s4_1"
  int stages;        ///< s
  /// Classical order certified by the generator: every order condition of eq. (f) (SEN-trees)
  /// up to h^order holds (generated/derivation.md lists them).
  int order;
  /// The leading local error term's size: the 2-norm of the residuals of every order condition
  /// of power order + 1 (the coefficients of h^(order+1) M^j F(tau), V^j = h^2j M^j counted in
  /// h, in the local errors of q and p; for the implicit family the V-dependence enters through
  /// these [V^j] terms, i.e. it is the h -> 0 constant at fixed M). NaN if every condition the
  /// generator checked holds.
  double error_constant;
  bool rkn;               ///< true: V -> 0 limit (constant coefficients, force -Mq - grad U)
  bool explicit_method;   ///< abar_ii = 0: a splitting method (exact linear flow and kicks)
  bool paper;             ///< a method of the source paper (or its V -> 0 limit)
  const char* reference;  ///< where the method comes from
  /// For H = A + eps B: generalized_order[K-1] is the order in h of the eps^K terms of the
  /// local error (certified, capped at the powers checked); empty for RKN limits.
  const int* generalized_order;
  /// generalized_error_constant[K-1]: the same norm over the trees with K f-vertices at power
  /// generalized_order[K-1] + 1 (NaN where none of them fails up to the powers checked).
  const double* generalized_error_constant;
  int ngeneralized;
  const double* c;             ///< nodes c_1..c_s
  const double* d;             ///< symplectic weights d_1..d_s of Theorem 2, eq. (g)
  const char* const* c_exact;  ///< c_i in GiNaC syntax (exact, or a decimal of >= 45 digits)
  const char* const* d_exact;  ///< d_i in GiNaC syntax
  /// Evaluates b[s], bbar[s], abar[s(s+1)/2] at v = h^2 lambda >= 0 (v away from a pole).
  void (*coefficients)(double v, double* b, double* bbar, double* abar);
  const double* series;             ///< [ncoef][kSeriesTerms] Taylor coefficients in v
  const char* const* closed_forms;  ///< [ncoef] closed forms, GiNaC syntax in v and phi(j,w*v)
  const double* poles;              ///< real poles in (0, kPoleSearchMax], ascending
  int npoles;
  /// Modified kicks (explicit methods only): e_1..e_s, stage i kicks
  /// p -= h (d_i grad U + h^2 e_i G), G = grad(|grad U|^2) = 2 Hess(U) grad U (methods.spec's
  /// `modified`); nullptr for plain kicks.
  const double* modified = nullptr;
  /// Processed methods psi = pi o K o pi^-1 (explicit; the fields above are the kernel K, order
  /// and the error constants psi's): the pre-processor pi^-1, which the runtime applies to a
  /// user's state before the kernel steps: for k = 0 .. npre-1, drift pre_drift[k] h (the exact
  /// flow of q'' + Mq = 0), then kick p -= h (pre_kick[k] grad U + h^2 pre_modified[k] G);
  /// then drift pre_drift[npre] h. pi (reversed, every coefficient negated) maps the kernel's
  /// state to every state a user sees. nullptr and npre = 0: not processed.
  const double* pre_drift = nullptr;     ///< [npre + 1]
  const double* pre_kick = nullptr;      ///< [npre]
  const double* pre_modified = nullptr;  ///< [npre]
  int npre = 0;
  int kernel_order = 0;  ///< the kernel K's own classical order (processed methods)
};

/// All methods, in the order of methods.def.
extern const Table kTables[];
extern const int kNumTables;

}  // namespace erkn::generated
