// erkn-generate --json: the explicit methods as data for Method::load (runtime/src/method_load.cpp
// reads it and checks the claimed orders against the order conditions in long double).
#include <stdexcept>

#include "emit.hpp"

namespace erkn::gen {
namespace {

// Digits of c, d: beyond long double's 19, so the loaded values are the polished ones.
constexpr int kJsonDigits = 25;

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) out += (ch == '"' || ch == '\\') ? std::string("\\") + ch : std::string(1, ch);
  return out + "\"";
}

template <class T, class F>
std::string list(const std::vector<T>& xs, F f) {
  std::string out = "[";
  for (size_t i = 0; i < xs.size(); ++i) out += (i ? ", " : "") + f(xs[i]);
  return out + "]";
}

std::string method_json(const Derived& m) {
  auto decimal = [](const Qs& q) { return q.decimal(kJsonDigits); };
  auto exact = [](const Qs& q) { return quoted(q.to_string()); };
  auto integer = [](int x) { return std::to_string(x); };
  std::string out = "    {\"name\": " + quoted(m.spec.name) +
                    ", \"id\": " + quoted(identifier(m.spec.name)) +
                    ", \"kind\": \"explicit\", \"stages\": " + std::to_string(m.stages()) +
                    ",\n     \"order\": " + std::to_string(m.certificate.order) +
                    ", \"generalized_order\": " + list(m.certificate.generalized, integer) +
                    ",\n     \"source\": " + quoted(m.spec.source) +
                    ",\n     \"c\": " + list(m.c, decimal) + ",\n     \"d\": " + list(m.d, decimal);
  if (!m.e.empty()) out += ",\n     \"modified\": " + list(m.e, decimal);
  return out + ",\n     \"c_exact\": " + list(m.c, exact) +
         ",\n     \"d_exact\": " + list(m.d, exact) + "}";
}

}  // namespace

std::string methods_json(const std::vector<Derived>& methods) {
  std::string out = "{\"format\": \"erkn methods 1\", \"methods\": [\n";
  for (size_t k = 0; k < methods.size(); ++k) {
    if (methods[k].spec.kind != SpecKind::explicit_erkn)
      throw std::runtime_error(methods[k].spec.name +
                               ": --json writes explicit methods only (constant coefficients); "
                               "a diagonal implicit method's coefficients are functions of V");
    if (!methods[k].pre.empty())
      throw std::runtime_error(methods[k].spec.name +
                               ": --json writes unprocessed methods only (Method::load has no "
                               "processor): compile processed methods with erkn_add_methods");
    out += method_json(methods[k]) + (k + 1 < methods.size() ? ",\n" : "\n");
  }
  return out + "]}\n";
}

}  // namespace erkn::gen
