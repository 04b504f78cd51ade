// Method::load: explicit methods as data (the file `erkn-generate --json` writes), validated
// against the order conditions they claim before any of them joins the registry.
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <set>
#include <sstream>

#include "erkn/error.hpp"
#include "erkn/method.hpp"
#include "json_reader.hpp"
#include "method_registry.hpp"
#include "order_conditions.hpp"

namespace erkn {
namespace {

using detail::JsonValue;

// A loaded method's table and everything it points to; kept for the program's lifetime.
struct OwnedTable {
  std::string name, id, reference;
  std::vector<int> generalized;
  std::vector<double> generalized_error_constant;
  std::vector<double> c, d, series;
  std::vector<long double> c_long, d_long;  // for the validation
  std::vector<std::string> c_text, d_text, forms;
  std::vector<const char*> c_exact, d_exact, form_ptrs;
  generated::Table table{};
};

std::string number_text(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// One coefficient k * phi_j(w2 v) of the explicit family: its closed form and its series
// k sum_n (-w2 v)^n / (2n + j)!.
void add_coefficient(OwnedTable& t, double k, int j, double w2) {
  t.forms.push_back(k == 0 ? "0"
                           : "(" + number_text(k) + ")*phi(" + std::to_string(j) + ",(" +
                                 number_text(w2) + ")*v)");
  double term = k;
  for (int n = 0; n < generated::kSeriesTerms; ++n) {
    for (int m = 2 * n - 1 + j; n > 0 && m <= 2 * n + j; ++m) term /= m;
    t.series.push_back(term);
    term *= -w2;
  }
}

// Numbers of one array member: as doubles (what the method integrates with) and long doubles.
void read_numbers(const JsonValue& m, const std::string& key, const std::string& where, int s,
                  std::vector<double>& x, std::vector<long double>& x_long) {
  const JsonValue& a = m.at(key, where);
  if (a.type != JsonValue::Type::array || int(a.items.size()) != s)
    throw Error(where + ": '" + key + "' must be a list of " + std::to_string(s) + " numbers");
  for (const JsonValue& v : a.items) {
    const char* text = v.text.c_str();
    char* end = nullptr;
    x_long.push_back(std::strtold(text, &end));
    if (v.type != JsonValue::Type::number || *end != '\0' || !std::isfinite(x_long.back()))
      throw Error(where + ": '" + key + "' has the non-number '" + v.text + "'");
    x.push_back(std::strtod(text, nullptr));
  }
}

std::vector<std::string> strings(const JsonValue& m, const std::string& key) {
  std::vector<std::string> out;
  if (m.has(key))
    for (const JsonValue& v : m.members.at(key).items) out.push_back(v.text);
  return out;
}

int integer(const JsonValue& m, const std::string& key, const std::string& where) {
  const JsonValue& v = m.at(key, where);
  char* end = nullptr;
  const long x = std::strtol(v.text.c_str(), &end, 10);
  if (v.type != JsonValue::Type::number || *end != '\0' || x < 0 || x > 1000)
    throw Error(where + ": '" + key + "' must be a small non-negative integer");
  return int(x);
}

void fill_coefficients(OwnedTable& t) {
  const int s = int(t.c.size());
  for (int i = 0; i < s; ++i) add_coefficient(t, t.d[i], 0, (1 - t.c[i]) * (1 - t.c[i]));
  for (int i = 0; i < s; ++i)
    add_coefficient(t, t.d[i] * (1 - t.c[i]), 1, (1 - t.c[i]) * (1 - t.c[i]));
  for (int i = 0; i < s; ++i)
    for (int j = 0; j <= i; ++j) {
      const double dc = t.c[i] - t.c[j];
      add_coefficient(t, j < i ? t.d[j] * dc : 0.0, 1, dc * dc);
    }
}

// The order check of eq. (f) in long double: erkn::Error naming the first failing condition.
detail::OrderReport check_claim(const OwnedTable& t, int order, const std::string& where) {
  const detail::OrderReport r =
      detail::check_order(t.c_long, t.d_long, order, t.generalized, 64 * LDBL_EPSILON);
  if (r.failure.empty()) return r;
  std::string g;
  for (int x : t.generalized) g += (g.empty() ? "" : ",") + std::to_string(x);
  throw Error(where + ": claims order " + std::to_string(order) + " (generalized " + g + "), but " +
              r.failure);
}

// Points t.table's fields at t's own storage (the table a compiled method would carry).
void link_table(OwnedTable& t, int s, int order, const detail::OrderReport& r) {
  t.generalized_error_constant = r.generalized_error_constant;
  t.generalized_error_constant.resize(t.generalized.size(),
                                      std::numeric_limits<double>::quiet_NaN());
  for (auto& x : t.c_text) t.c_exact.push_back(x.c_str());
  for (auto& x : t.d_text) t.d_exact.push_back(x.c_str());
  for (auto& x : t.forms) t.form_ptrs.push_back(x.c_str());
  t.table = {t.name.c_str(),
             t.id.c_str(),
             s,
             order,
             r.error_constant,
             false,
             true,
             false,
             t.reference.c_str(),
             t.generalized.data(),
             t.generalized_error_constant.data(),
             int(t.generalized.size()),
             t.c.data(),
             t.d.data(),
             t.c_exact.data(),
             t.d_exact.data(),
             nullptr,
             t.series.data(),
             t.form_ptrs.data(),
             nullptr,
             0};
}

std::unique_ptr<OwnedTable> read_method(const JsonValue& m, const std::string& path) {
  auto t = std::make_unique<OwnedTable>();
  t->name = m.at("name", path).text;
  const std::string where = path + ": method '" + t->name + "'";
  t->id = m.has("id") ? m.members.at("id").text : t->name;
  t->reference = m.has("source") ? m.members.at("source").text : path;
  if (m.at("kind", where).text != "explicit")
    throw Error(where + ": kind '" + m.at("kind", where).text +
                "': only explicit methods (constant coefficients) load from data; a diagonal "
                "implicit method's coefficients are functions of V: compile it (erkn_add_methods)");
  const int s = integer(m, "stages", where), order = integer(m, "order", where);
  read_numbers(m, "c", where, s, t->c, t->c_long);
  read_numbers(m, "d", where, s, t->d, t->d_long);
  if (m.has("modified"))
    throw Error(where +
                ": modified kicks: the order check of a method file covers plain kicks only; "
                "compile a modified-kick method with erkn_add_methods (its order is then the "
                "generator's certificate)");
  for (const JsonValue& g : m.at("generalized_order", where).items)
    t->generalized.push_back(std::atoi(g.text.c_str()));
  t->c_text = strings(m, "c_exact"), t->d_text = strings(m, "d_exact");
  if (int(t->c_text.size()) != s || int(t->d_text.size()) != s)
    for (int i = 0; i < s; ++i)
      t->c_text.push_back(number_text(t->c[i])), t->d_text.push_back(number_text(t->d[i]));
  t->c_text.resize(size_t(s)), t->d_text.resize(size_t(s));
  const detail::OrderReport r = check_claim(*t, order, where);
  fill_coefficients(*t);
  link_table(*t, s, order, r);
  return t;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read method file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::vector<Method> Method::load(const std::string& path) {
  static std::deque<std::unique_ptr<OwnedTable>> owned;  // the loaded tables live on
  const JsonValue doc = detail::parse_json(read_file(path), path);
  const JsonValue& list = doc.at("methods", path);
  std::vector<std::unique_ptr<OwnedTable>> tables;
  std::set<std::string> names;
  for (const JsonValue& m : list.items) {
    tables.push_back(read_method(m, path));
    detail::check_addable(tables.back()->table);
    const OwnedTable& t = *tables.back();
    if (names.count(t.name) || names.count(t.id))
      throw Error(path + ": method '" + t.name + "' is listed twice");
    names.insert(t.name), names.insert(t.id);
  }
  std::vector<Method> out;
  for (auto& t : tables) {
    owned.push_back(std::move(t));
    out.push_back(add(owned.back()->table));
  }
  return out;
}

}  // namespace erkn
