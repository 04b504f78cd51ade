#include "erkn/stability.hpp"

#include <algorithm>
#include <cmath>

#include "erkn/error.hpp"
#include "format.hpp"
#include "method_registry.hpp"
#include "phi.hpp"
#include "stage_phases.hpp"

namespace erkn {

double StabilityMatrix::spectral_radius() const {
  const double tr = trace(), dt = det(), disc = tr * tr - 4 * dt;
  if (disc < 0) return std::sqrt(dt);  // complex pair: |lambda|^2 = det
  const double r = std::sqrt(disc);
  // The larger root without cancellation; the smaller one is det / larger.
  const double big = 0.5 * (std::abs(tr) + r);
  return big == 0 ? 0.0 : std::max(big, std::abs(dt / big));
}

bool StabilityMatrix::finite() const {
  return std::isfinite(s11) && std::isfinite(s12) && std::isfinite(s21) && std::isfinite(s22);
}

double StabilityMatrix::det_relative_deviation() const {
  const double scale = std::abs(s11 * s22) + std::abs(s12 * s21);
  return std::abs(det() - 1) / std::max(scale, 1e-300);
}

namespace detail {

StagePhases stage_phases(const Method& method, const Coefficients& k, double V) {
  // RKN: the V = 0 formula with the whole force (V + z) as the "nonlinearity".
  StagePhases ph;
  ph.k = &k, ph.rkn = method.kind() == Kind::rkn, ph.V = V, ph.v = ph.rkn ? 0.0 : V;
  for (int i = 0; i < k.s; ++i) {
    const double c = k.c[i];
    ph.x0[i] = detail::phi0(c * c * ph.v), ph.y0[i] = c * detail::phi1(c * c * ph.v);
  }
  ph.p0 = detail::phi0(ph.v), ph.p1 = detail::phi1(ph.v);
  if (method.has_modified_kicks()) {
    ph.modified = true, ph.unit.s = k.s;
    const std::array<double, kMaxStages> ones = [] {
      std::array<double, kMaxStages> x;
      x.fill(1.0);
      return x;
    }();
    explicit_family(k.c.data(), ones.data(), k.s, ph.v, ph.unit.b.data(), ph.unit.bbar.data(),
                    ph.unit.abar_packed.data());
    for (int i = 0; i < k.s; ++i) ph.d[i] = method.table().d[i], ph.e[i] = method.modified()[i];
  }
  return ph;
}

// The coefficients of a modified-kick method at z: column j's per-unit values times d_j + 2 z e_j.
Coefficients modified_coefficients(const StagePhases& ph, double z) {
  Coefficients k = ph.unit;
  for (int j = 0; j < k.s; ++j) {
    const double w = ph.d[j] + 2 * z * ph.e[j];
    k.b[j] *= w, k.bbar[j] *= w;
    for (int i = j; i < k.s; ++i) k.abar_packed[Coefficients::packed(i, j)] *= w;
  }
  return k;
}

StabilityMatrix stability_matrix(const StagePhases& ph, double z) {
  const Coefficients modified = ph.modified ? modified_coefficients(ph, z) : Coefficients{};
  const Coefficients& k = ph.modified ? modified : *ph.k;
  const double v = ph.v, w = ph.rkn ? ph.V + z : z;
  const int s = k.s;
  // x = N^-1 phi0(c^2 v), y = N^-1 (c phi1(c^2 v)), N = I + w Abar lower triangular.
  std::array<double, kMaxStages> x{}, y{};
  for (int i = 0; i < s; ++i) {
    double xi = ph.x0[i], yi = ph.y0[i];
    for (int j = 0; j < i; ++j) xi -= w * k.abar(i, j) * x[j], yi -= w * k.abar(i, j) * y[j];
    const double nii = 1 + w * k.abar(i, i);
    x[i] = xi / nii;
    y[i] = yi / nii;
  }
  double bbx = 0, bby = 0, bx = 0, by = 0;
  for (int i = 0; i < s; ++i) {
    bbx += k.bbar[i] * x[i], bby += k.bbar[i] * y[i];
    bx += k.b[i] * x[i], by += k.b[i] * y[i];
  }
  return {ph.p0 - w * bbx, ph.p1 - w * bby, -v * ph.p1 - w * bx, ph.p0 - w * by};
}

}  // namespace detail

namespace {

StabilityMatrix product(const StabilityMatrix& a, const StabilityMatrix& b) {
  return {a.s11 * b.s11 + a.s12 * b.s21, a.s11 * b.s12 + a.s12 * b.s22,
          a.s21 * b.s11 + a.s22 * b.s21, a.s21 * b.s12 + a.s22 * b.s22};
}

// The exact flow of y'' + omega^2 y = 0 over tau h on (y, h y'): theta = tau sqrt(V).
StabilityMatrix drift(double tau, double V) {
  const double w = std::sqrt(V), th = tau * w;
  const double sinc = w == 0 ? tau : std::sin(th) / w;
  return {std::cos(th), sinc, -V * sinc, std::cos(th)};
}

// The processor pi = pi^-1 reversed with every coefficient negated (erkn/table.hpp); a kick
// p -= h (y grad U + h^2 v G) on the test equation adds -(y z + 2 v z^2) y to h y'.
StabilityMatrix processor_matrix(const generated::Table& t, double V, double z) {
  StabilityMatrix P = drift(-t.pre_drift[t.npre], V);
  for (int k = t.npre - 1; k >= 0; --k) {
    const double y = -t.pre_kick[k], v = -t.pre_modified[k];
    P = product(drift(-t.pre_drift[k], V), product({1, 0, -(y * z + 2 * v * z * z), 1}, P));
  }
  return P;
}

}  // namespace

StabilityMatrix stability_matrix(const Method& method, const Coefficients& k, double V, double z) {
  const StabilityMatrix S = detail::stability_matrix(detail::stage_phases(method, k, V), z);
  if (!method.is_processed()) return S;
  const StabilityMatrix P = processor_matrix(method.table(), V, z);
  const double d = P.det();  // 1 up to round-off (symplectic)
  return product(product(P, S), {P.s22 / d, -P.s12 / d, -P.s21 / d, P.s11 / d});
}

StabilityMatrix stability_matrix(const Method& method, double V, double z) {
  if (!std::isfinite(V) || V < 0) throw Error("stability_matrix: V = h^2 omega^2 must be >= 0");
  return stability_matrix(method, method.at(method.kind() == Kind::rkn ? 0.0 : V), V, z);
}

StabilityClass classify(const StabilityMatrix& S, double tau) {
  if (!S.finite()) return StabilityClass::singular;
  const double tr = std::abs(S.trace());
  if (S.det_relative_deviation() > kDetTolerance) {
    const double rho = S.spectral_radius();
    if (!std::isfinite(rho)) return StabilityClass::singular;
    if (rho > 1 + tau) return StabilityClass::unstable;
    if (rho < 1 - tau) return StabilityClass::contractive;
    return StabilityClass::marginal;
  }
  if (tr < 2 - tau) return StabilityClass::periodic;
  if (tr <= 2 + tau) return StabilityClass::marginal;
  return StabilityClass::unstable;
}

std::string_view to_string(StabilityClass c) {
  switch (c) {
    case StabilityClass::periodic:
      return "periodic";
    case StabilityClass::marginal:
      return "marginal";
    case StabilityClass::unstable:
      return "unstable";
    case StabilityClass::contractive:
      return "contractive";
    case StabilityClass::singular:
      return "singular";
    case StabilityClass::pole:
      return "pole";
  }
  return "?";
}

StabilityGrid stability_grid(const Method& method, double vmax, double zmin, double zmax, int nv,
                             int nz) {
  if (!(vmax > 0) || !std::isfinite(vmax) || !(zmax > zmin) || !std::isfinite(zmin) ||
      !std::isfinite(zmax) || nv < 2 || nz < 2)
    throw Error("stability_grid: need vmax > 0, zmax > zmin (finite) and at least 2x2 points");
  if ((!method.entire() && vmax > generated::kPoleSearchMax) || !std::isfinite(zmax - zmin))
    throw Error("stability_grid: vmax = " + format(vmax) + " or the z range [" + format(zmin) +
                ", " + format(zmax) + "] is too large: the method's poles are known for V <= " +
                format(generated::kPoleSearchMax) + " and zmax - zmin must be finite");
  StabilityGrid g;
  g.vmax = vmax, g.zmin = zmin, g.zmax = zmax, g.nv = nv, g.nz = nz;
  g.points.resize(size_t(nv) * nz);
  const bool rkn = method.kind() == Kind::rkn;
  const Coefficients k0 = method.at(0.0);
  for (int i = 0; i < nv; ++i) {
    const double V = vmax * i / (nv - 1);
    Coefficients k = k0;
    bool at_pole = false;
    if (!rkn) {
      try {
        k = method.at(V);
      } catch (const Error&) {
        at_pole = true;
      }
    }
    for (int j = 0; j < nz; ++j) {
      StabilityPoint& p = g.points[size_t(i) * nz + j];
      p.V = V;
      p.z = zmin + (zmax - zmin) * j / (nz - 1);
      if (at_pole) {
        p.trace = p.det = p.rho = std::nan("");
        p.cls = StabilityClass::pole;
        continue;
      }
      const StabilityMatrix S = stability_matrix(method, k, V, p.z);
      p.trace = S.trace(), p.det = S.det(), p.rho = S.spectral_radius();
      p.cls = classify(S);
      if (!S.finite()) continue;
      const double dev = std::abs(p.det - 1);
      g.max_det_deviation = std::max(g.max_det_deviation, dev);
      g.max_det_relative_deviation =
          std::max(g.max_det_relative_deviation, S.det_relative_deviation());
      if (bounded_region(p.cls))
        g.max_det_deviation_bounded = std::max(g.max_det_deviation_bounded, dev);
    }
  }
  return g;
}

}  // namespace erkn
