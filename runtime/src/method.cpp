#include "erkn/method.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>

#include "erkn/error.hpp"

namespace erkn {
namespace {

const std::array kAll = {
#define ERKN_METHOD(id, name, stages, order, kind) \
  Method(MethodId::id, &generated::kTables[int(MethodId::id)]),
#include "erkn/generated/methods.def"
#undef ERKN_METHOD
};

std::string format_double(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

}  // namespace

const Method& Method::get(MethodId id) {
  const auto index = static_cast<std::underlying_type_t<MethodId>>(id);
  if (index < 0 || size_t(index) >= kAll.size())
    throw Error("unknown method id " + std::to_string(index) + "; ids are 0.." +
                std::to_string(kAll.size() - 1));
  return kAll[size_t(index)];
}

std::span<const Method> Method::all() { return kAll; }

const Method& Method::by_name(std::string_view name) {
  for (const Method& m : kAll)
    if (m.name() == name || m.id_name() == name) return m;
  std::string known;
  for (const Method& m : kAll) known += (known.empty() ? "" : ", ") + std::string(m.name());
  throw Error("unknown method '" + std::string(name) + "'; known methods: " + known);
}

std::string_view Method::kind_name() const {
  return kind() == Kind::rkn ? "rkn" : is_explicit() ? "explicit" : "erkn";
}

double Method::nearest_pole(double v) const {
  double best = -1.0;
  for (double p : poles())
    if (best < 0 || std::abs(p - v) < std::abs(best - v)) best = p;
  return best;
}

double Method::pole_within(double v, double tolerance) const {
  double p = nearest_pole(v);
  return p > 0 && std::abs(v - p) <= tolerance * p ? p : -1.0;
}

Coefficients Method::at(double v, double pole_tolerance) const {
  if (!std::isfinite(v)) throw Error("coefficient argument v = h^2*lambda is not finite");
  if (v < 0)
    throw Error("coefficient argument v = h^2*lambda = " + format_double(v) + " is negative");
  // (NaN or a negative tolerance would make every pole test false: coefficients on a pole.)
  if (!(pole_tolerance >= 0) || !std::isfinite(pole_tolerance))
    throw Error("Method::at: pole_tolerance = " + format_double(pole_tolerance) +
                " must be finite and >= 0");
  if (kind() == Kind::erkn) {
    if (!entire() && v > generated::kPoleSearchMax)
      throw Error(std::string(name()) + ": v = h^2*lambda = " + format_double(v) +
                  " exceeds the range where poles are known (v <= " +
                  format_double(generated::kPoleSearchMax) + ")");
    if (double p = pole_within(v, pole_tolerance); p > 0)
      throw Error(std::string(name()) + ": coefficients are singular at v = h^2*lambda = " +
                  format_double(v) + ", within a relative " + format_double(pole_tolerance) +
                  " of the pole v = " + format_double(p));
  }
  Coefficients k;
  k.s = stages();
  for (int i = 0; i < k.s; ++i) k.c[i] = table_->c[i];
  table_->coefficients(v, k.b.data(), k.bbar.data(), k.abar_packed.data());
  return k;
}

double Method::series(int index, int k) const {
  if (index < 0 || index >= num_coefficients() || k < 0 || k >= generated::kSeriesTerms)
    throw Error("series index out of range");
  return table_->series[index * generated::kSeriesTerms + k];
}

}  // namespace erkn
