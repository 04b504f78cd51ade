#include "modified_force.hpp"

#include <string>

#include "erkn/error.hpp"

namespace erkn::detail {

void require_modified_force(const Method& method, const System& system) {
  if (!method.has_modified_kicks() || system.hessian_vector_product || system.hessian) return;
  std::string plain;
  for (const Method& m : Method::all())
    if (m.is_explicit() && !m.has_modified_kicks())
      plain += (plain.empty() ? "" : ", ") + std::string(m.name());
  throw Error(std::string(method.name()) +
              " has modified kicks (grad(|grad U|^2) = 2 Hess U grad U): set "
              "System::hessian_vector_product (Hess U(q) v) or System::hessian; the methods "
              "with plain kicks need neither (the explicit ones: " +
              plain + ")");
}

namespace {

// KickWeights::fsal(): the first kick's weight on the last stage's force (c_1 = 0, c_s = 1), or
// none. h2e: the kicks' h^2 e_i. (File-local, so that it is inlined: out of line its optional
// came back through the stack, a one-byte store read as eight bytes, a store-forwarding stall
// that cost ~4 % of a construction at d = 1, perf.)
std::optional<double> fsal_factor(const Method& method, const std::array<double, kMaxStages>& h2e) {
  const int s = method.stages();
  const double *c = method.table().c, *d = method.table().d;
  if (s < 2 || c[0] != 0 || c[s - 1] != 1) return std::nullopt;
  const double e1 = h2e[0], es = h2e[size_t(s - 1)];
  if (e1 == 0 && es == 0) return d[0];  // (plain kicks: force g, weight d_1)
  // F_1 = d_1 g + e_1 G = r F_s exactly when (d_1, e_1) = r (d_s, e_s).
  if (e1 == 0 || es == 0) return std::nullopt;
  const double r = e1 / es;
  if (d[0] != r * d[s - 1]) return std::nullopt;
  return r;
}

}  // namespace

KickWeights::KickWeights(const Method& method, double h) : s_(method.stages()), h_(h) {
  const std::span<const double> e = method.modified();
  for (int i = 0; i < method.stages(); ++i) {
    const bool modified = !e.empty() && e[size_t(i)] != 0;
    weight_[size_t(i)] = modified ? 1.0 : method.table().d[i];
    h2e_[size_t(i)] = modified ? h * h * e[size_t(i)] : 0.0;
  }
  fsal_ = fsal_factor(method, h2e_);
}

}  // namespace erkn::detail
