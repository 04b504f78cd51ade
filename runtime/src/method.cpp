#include "erkn/method.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <type_traits>

#include "erkn/error.hpp"
#include "format.hpp"
#include "method_registry.hpp"

namespace erkn {
namespace {

// erkn's own methods first; Method::add appends. A deque: references stay valid.
std::deque<Method>& registry() {
  static std::deque<Method> all = {
#define ERKN_METHOD(id, name, stages, order, kind) \
  Method(MethodId::id, &generated::kTables[int(MethodId::id)]),
#include "erkn/generated/methods.def"
#undef ERKN_METHOD
  };
  return all;
}

double sinc(double t) { return t == 0.0 ? 1.0 : std::sin(t) / t; }

}  // namespace

const Method& Method::get(MethodId id) {
  const auto index = static_cast<std::underlying_type_t<MethodId>>(id);
  if (index < 0 || size_t(index) >= registry().size())
    throw Error("unknown method id " + std::to_string(index) + "; ids are 0.." +
                std::to_string(registry().size() - 1));
  return registry()[size_t(index)];
}

const std::deque<Method>& Method::all() { return registry(); }

const Method& Method::by_name(std::string_view name) {
  for (const Method& m : registry())
    if (m.name() == name || m.id_name() == name) return m;
  std::string known;
  for (const Method& m : registry()) known += (known.empty() ? "" : ", ") + std::string(m.name());
  throw Error("unknown method '" + std::string(name) + "'; known methods: " + known);
}

void detail::check_addable(const generated::Table& table) {
  const std::string name = table.name ? table.name : "";
  if (name.empty() || !table.id || !table.c || !table.d)
    throw Error("method table '" + name + "' lacks its name, id, nodes c or weights d");
  if (table.modified && (!table.explicit_method || table.rkn))
    throw Error(name +
                ": modified kicks (grad(|grad U|^2)) are integrated by the explicit stepper "
                "only; this table is " +
                (table.rkn ? "an RKN limit" : "implicit"));
  if (table.npre < 0 ||
      (table.npre > 0 && (!table.explicit_method || table.rkn || !table.pre_drift ||
                          !table.pre_kick || !table.pre_modified)))
    throw Error(name + ": a processor (npre = " + std::to_string(table.npre) +
                ") needs an explicit table with pre_drift, pre_kick and pre_modified");
  if (table.stages < 1 || table.stages > kMaxStages)
    throw Error(name + ": " + std::to_string(table.stages) + " stages; this runtime takes 1.." +
                std::to_string(kMaxStages) + " (kMaxStages, from erkn's own largest method)");
  if (!table.coefficients && !table.explicit_method)
    throw Error(name + ": an implicit method needs its emitted coefficient function");
  if (!table.closed_forms)  // (the steppers read which abar_ii are identically zero from them)
    throw Error(name + ": lacks its closed forms (closed_forms: b, bbar and abar in GiNaC syntax)");
  for (const Method& m : registry())
    if (m.name() == name || m.id_name() == table.id || m.name() == table.id || m.id_name() == name)
      throw Error("cannot add method '" + name + "' (id " + table.id + "): '" +
                  std::string(m.name()) + "' is already listed under that name or id");
}

const Method& Method::add(const generated::Table& table) {
  detail::check_addable(table);
  registry().emplace_back(MethodId(registry().size()), &table);
  return registry().back();
}

std::string_view Method::kind_name() const {
  return kind() == Kind::rkn ? "rkn" : is_explicit() ? "explicit" : "erkn";
}

// The poles ascend (generated::Table::poles): the nearest is one of the two around v, the lower
// on a tie (as a scan from the lowest keeping the first of equally near ones). (Scanned, the 19
// poles of SERKN2s3 were ~270 instructions per eigenvalue of each implicit Integrator's
// construction, P3: callgrind.)
double Method::nearest_pole(double v) const {
  const std::span<const double> p = poles();
  if (p.empty()) return -1.0;
  const auto above = std::lower_bound(p.begin(), p.end(), v);
  if (above == p.begin()) return *above;
  if (above == p.end()) return p.back();
  const double below = *(above - 1);
  return std::abs(*above - v) < std::abs(below - v) ? *above : below;
}

double Method::pole_within(double v, double tolerance) const {
  double p = nearest_pole(v);
  return p > 0 && std::abs(v - p) <= tolerance * p ? p : -1.0;
}

void detail::explicit_family(const double* c, const double* d, int s, double v, double* b,
                             double* bbar, double* abar) {
  // The explicit family (docs/design.md): b_i = d_i phi0((1-c_i)^2 v), bbar_i = d_i (1-c_i)
  // phi1((1-c_i)^2 v), abar_ij = d_j (c_i-c_j) phi1((c_i-c_j)^2 v), abar_ii = 0; phi0(w^2 v) =
  // cos(w x), phi1(w^2 v) = sinc(w x), x = sqrt(v), as the emitted functions evaluate them.
  const double x = std::sqrt(v);
  for (int i = 0; i < s; ++i) {
    b[i] = d[i] * std::cos(std::abs(1 - c[i]) * x);
    bbar[i] = d[i] * (1 - c[i]) * sinc(std::abs(1 - c[i]) * x);
    for (int j = 0; j < i; ++j)
      abar[Coefficients::packed(i, j)] = d[j] * (c[i] - c[j]) * sinc(std::abs(c[i] - c[j]) * x);
    abar[Coefficients::packed(i, i)] = 0.0;
  }
}

void Method::evaluate(double v, double* b, double* bbar, double* abar) const {
  if (table_->coefficients) return table_->coefficients(v, b, bbar, abar);
  detail::explicit_family(table_->c, table_->d, stages(), v, b, bbar, abar);
}

Coefficients Method::at(double v, double pole_tolerance) const {
  if (!std::isfinite(v)) throw Error("coefficient argument v = h^2*lambda is not finite");
  if (v < 0) throw Error("coefficient argument v = h^2*lambda = " + format(v, 17) + " is negative");
  // (NaN or a negative tolerance would make every pole test false: coefficients on a pole.)
  if (!(pole_tolerance >= 0) || !std::isfinite(pole_tolerance))
    throw Error("Method::at: pole_tolerance = " + format(pole_tolerance, 17) +
                " must be finite and >= 0");
  if (kind() == Kind::erkn) {
    if (!entire() && v > generated::kPoleSearchMax)
      throw Error(std::string(name()) + ": v = h^2*lambda = " + format(v, 17) +
                  " exceeds the range where poles are known (v <= " +
                  format(generated::kPoleSearchMax, 17) + ")");
    if (double p = pole_within(v, pole_tolerance); p > 0)
      throw Error(std::string(name()) + ": coefficients are singular at v = h^2*lambda = " +
                  format(v, 17) + ", within a relative " + format(pole_tolerance, 17) +
                  " of the pole v = " + format(p, 17));
  }
  Coefficients k;
  k.s = stages();
  for (int i = 0; i < k.s; ++i) k.c[i] = table_->c[i];
  evaluate(v, k.b.data(), k.bbar.data(), k.abar_packed.data());
  return k;
}

double Method::series(int index, int k) const {
  if (index < 0 || index >= num_coefficients() || k < 0 || k >= generated::kSeriesTerms)
    throw Error("series index out of range");
  return table_->series[index * generated::kSeriesTerms + k];
}

}  // namespace erkn
