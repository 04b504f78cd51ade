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

KickWeights::KickWeights(const Method& method, double h) : s_(method.stages()), h_(h) {
  const std::span<const double> e = method.modified();
  for (int i = 0; i < method.stages(); ++i) {
    const bool modified = !e.empty() && e[size_t(i)] != 0;
    weight_[size_t(i)] = modified ? 1.0 : method.table().d[i];
    h2e_[size_t(i)] = modified ? h * h * e[size_t(i)] : 0.0;
  }
  fsal_ = fsal_factor(method);
}

std::optional<double> KickWeights::fsal_factor(const Method& method) const {
  const int s = method.stages();
  const double *c = method.table().c, *d = method.table().d;
  if (s < 2 || c[0] != 0 || c[s - 1] != 1) return std::nullopt;
  const double e1 = h2e(0), es = h2e(s - 1);
  if (e1 == 0 && es == 0) return d[0];  // (plain kicks: force g, weight d_1)
  // F_1 = d_1 g + e_1 G = r F_s exactly when (d_1, e_1) = r (d_s, e_s).
  if (e1 == 0 || es == 0) return std::nullopt;
  const double r = e1 / es;
  if (d[0] != r * d[s - 1]) return std::nullopt;
  return r;
}

}  // namespace erkn::detail
