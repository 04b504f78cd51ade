#include "symbolic_support.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

using namespace GiNaC;
using erkn::gen::phi;

namespace erkn::symtest {
namespace {

std::string str(const ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

std::map<std::string, symbol>& registry() {
  static std::map<std::string, symbol> table = [] {
    std::map<std::string, symbol> t;
    for (int i = 1; i <= generated::kMaxStages; ++i) {
      for (const char* p : {"b", "bbar", "c", "d"}) {
        std::string n = p + std::to_string(i);
        t.emplace(n, symbol(n));
      }
      for (int j = 1; j <= i; ++j) t.emplace(abar_name(i, j), symbol(abar_name(i, j)));
    }
    return t;
  }();
  return table;
}

Qs qs_pow(const Qs& x, long n) {
  Qs base = n < 0 ? x.inverse() : x, out(1);
  for (long k = 0; k < (n < 0 ? -n : n); ++k) out = out * base;
  return out;
}

// sqrt(p/q) = sqrt(p q)/q = (k/q) sqrt(m), p q = k^2 m with m square-free.
Qs sqrt_rational(const numeric& r) {
  if (!r.is_rational() || r.is_negative()) throw std::invalid_argument("sqrt of " + str(r));
  numeric pq = r.numer() * r.denom();
  long n = pq.to_long(), k = 1;
  for (long f = 2; f * f <= n; ++f)
    while (n % (f * f) == 0) n /= f * f, k *= f;
  if (n == 1) return Qs(numeric(k) / r.denom());
  return Qs(0, numeric(k) / r.denom(), int(n));
}

int series_length(const std::vector<Series>& coefficients) {
  int n = 0;
  for (const Series& s : coefficients) n = std::max(n, int(s.size()));
  return n;
}

Series constant_series(const Qs& q, int n) {
  Series s(n, Qs(0));
  if (n > 0) s[0] = q;
  return s;
}

Series inverse_series(const Series& x) {
  if (x.empty() || x[0].is_zero()) throw std::domain_error("series inverse: zero constant term");
  Series y(x.size(), Qs(0));
  Qs inv = x[0].inverse();
  y[0] = inv;
  for (size_t k = 1; k < x.size(); ++k) {
    Qs sum(0);
    for (size_t j = 1; j <= k; ++j) sum = sum + x[j] * y[k - j];
    y[k] = -(sum * inv);
  }
  return y;
}

// Coefficients of v^0..v^(K-1) of an expression without negative powers of v, by series().
Series raw_series(const ex& e, int K) {
  const symbol& v = vsym();
  ex p = expand(series_to_poly(e.series(v == 0, K)));
  if (p.ldegree(v) < 0) throw std::domain_error("negative power of v in " + str(e));
  Series out(K, Qs(0));
  for (int k = 0; k < K; ++k) out[k] = exact_number(p.coeff(v, k));
  return out;
}

}  // namespace

std::string abar_name(int i, int j) {
  // abar21 as the paper writes it; from 10 stages on the indices need a separator (abar11_1).
  const std::string sep = i >= 10 || j >= 10 ? "_" : "";
  return "abar" + std::to_string(i) + sep + std::to_string(j);
}

namespace {
// A decimal literal in a table's text: [begin, end) of "123.456e-7", its digits without the point
// and the power of ten they are scaled by; found only where no name continues into it.
struct Decimal {
  size_t begin = 0, end = 0;
  std::string digits;
  long exponent = 0;
};
bool is_name_char(char ch) { return std::isalnum((unsigned char)ch) || ch == '_'; }
std::vector<Decimal> decimals(const std::string& t) {
  std::vector<Decimal> out;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!std::isdigit((unsigned char)t[i]) || (i > 0 && is_name_char(t[i - 1]))) continue;
    size_t j = i;
    while (j < t.size() && std::isdigit((unsigned char)t[j])) ++j;
    if (j == t.size() || t[j] != '.') {
      i = j;
      continue;
    }
    Decimal d{i, j + 1, t.substr(i, j - i), 0};
    for (j = j + 1; j < t.size() && std::isdigit((unsigned char)t[j]); ++j)
      d.digits += t[j], --d.exponent;
    size_t k = j + 1;
    if (j < t.size() && (t[j] == 'e' || t[j] == 'E')) {
      if (k < t.size() && (t[k] == '-' || t[k] == '+')) ++k;
      size_t first = k;
      while (k < t.size() && std::isdigit((unsigned char)t[k])) ++k;
      if (k > first) d.exponent += std::stol(t.substr(j + 1, k - j - 1)), j = k;
    }
    d.end = j;
    out.push_back(d);
    i = j;
  }
  return out;
}
}  // namespace

std::string exact_text(const std::string& text) {
  std::string out;
  size_t at = 0;
  for (const Decimal& d : decimals(text)) {
    long e = d.exponent;
    out += text.substr(at, d.begin - at) + "(" + d.digits + (e < 0 ? "/" : "*") + "10^" +
           std::to_string(e < 0 ? -e : e) + ")";
    at = d.end;
  }
  return out + text.substr(at);
}

const symbol& vsym() {
  static const symbol v("v");
  return v;
}

const symbol& sym(const std::string& name) {
  auto& table = registry();
  auto it = table.find(name);
  if (it == table.end()) it = table.emplace(name, symbol(name)).first;
  return it->second;
}

ex parse(const std::string& text) {
  symtab table;
  table["v"] = vsym();
  for (const auto& [name, s] : registry()) table[name] = s;
  parser read(table, true);
  return read(exact_text(text));
}

Qs exact_number(const ex& e) {
  if (is_a<numeric>(e)) return Qs(ex_to<numeric>(e));
  if (is_a<GiNaC::add>(e)) {
    Qs r(0);
    for (size_t i = 0; i < e.nops(); ++i) r = r + exact_number(e.op(i));
    return r;
  }
  if (is_a<GiNaC::mul>(e)) {
    Qs r(1);
    for (size_t i = 0; i < e.nops(); ++i) r = r * exact_number(e.op(i));
    return r;
  }
  if (is_a<GiNaC::power>(e) && is_a<numeric>(e.op(1))) {
    numeric x = ex_to<numeric>(e.op(1));
    if (x.is_integer()) return qs_pow(exact_number(e.op(0)), x.to_long());
    if (x.denom() == 2 && is_a<numeric>(e.op(0)))
      return qs_pow(sqrt_rational(ex_to<numeric>(e.op(0))), x.numer().to_long());
  }
  throw std::invalid_argument("not an exact number in Q(sqrt(s)): " + str(e));
}

Series ginac_taylor(const ex& e, int n) {
  // Split off the factors with negative integer exponents: the emitted quotients are
  // (numerator)/(denominator) with a denominator that vanishes at v = 0.
  ex num = 1, den = 1;
  auto split = [&](const ex& f) {
    if (is_a<GiNaC::power>(f) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_integer() &&
        ex_to<numeric>(f.op(1)).is_negative() && f.op(0).has(vsym()))
      den *= pow(f.op(0), -f.op(1));
    else
      num *= f;
  };
  if (is_a<GiNaC::mul>(e))
    for (size_t i = 0; i < e.nops(); ++i) split(e.op(i));
  else
    split(e);
  const int K = n + 8;
  Series N = raw_series(num, K), D = raw_series(den, K);
  int m = 0;
  while (m < K && D[m].is_zero()) ++m;
  if (m > K - n) throw std::domain_error("denominator vanishes to high order: " + str(den));
  for (int k = 0; k < m; ++k)
    if (!N[k].is_zero()) throw std::domain_error("pole at v = 0: " + str(e));
  // q_k = (N_{k+m} - sum_{j=1..k} D_{m+j} q_{k-j}) / D_m
  Series q(n, Qs(0));
  Qs inv = D[m].inverse();
  for (int k = 0; k < n; ++k) {
    Qs sum = N[k + m];
    for (int j = 1; j <= k; ++j) sum = sum - D[m + j] * q[k - j];
    q[k] = sum * inv;
  }
  return q;
}

Series normal_form_taylor(const ex& e, int n) {
  return gen::taylor(gen::to_rational(e, {}, vsym()), n);
}

Series phi_series(int j, const Qs& w, int n) {
  Series s(n, Qs(0));
  Qs wk(1);
  for (int k = 0; k < n; ++k) {
    s[k] = (k % 2 ? Qs(-1) : Qs(1)) * wk / Qs(factorial(numeric(2 * k + j)));
    wk = wk * w;
  }
  return s;
}

Series add(const Series& x, const Series& y) {
  Series z(std::max(x.size(), y.size()), Qs(0));
  for (size_t k = 0; k < z.size(); ++k)
    z[k] = (k < x.size() ? x[k] : Qs(0)) + (k < y.size() ? y[k] : Qs(0));
  return z;
}

Series mul(const Series& x, const Series& y) {
  size_t n = std::min(x.size(), y.size());
  Series z(n, Qs(0));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; i + j < n; ++j) z[i + j] = z[i + j] + x[i] * y[j];
  return z;
}

// ---------------------------------------------------------------------------------------------

std::vector<std::string> coefficient_names(int s) {
  std::vector<std::string> names;
  for (int i = 1; i <= s; ++i) names.push_back("b" + std::to_string(i));
  for (int i = 1; i <= s; ++i) names.push_back("bbar" + std::to_string(i));
  for (int i = 1; i <= s; ++i)
    for (int j = 1; j <= i; ++j) names.push_back(abar_name(i, j));
  return names;
}

int Method::index(const std::string& coefficient) const {
  for (size_t k = 0; k < names.size(); ++k)
    if (names[k] == coefficient) return int(k);
  throw std::invalid_argument(name + " has no coefficient " + coefficient);
}

GiNaC::numeric Method::tolerance() const {
  if (digits == 0) return numeric(0);
  // The generator certifies a condition when |residual| <= 1e-45 (60-digit arithmetic): more
  // digits than 48 do not make the numbers meet their conditions more closely than that.
  return numeric(1) / GiNaC::pow(numeric(10), numeric(std::min(digits, kCertifiedDigits) - 3));
}

bool Method::negligible(const Qs& r) const {
  if (digits == 0) return r.is_zero();
  return abs(r.to_float(100)) <= tolerance();
}

namespace {
// The most significant digits of a decimal literal in the text (the precision the table is
// written in; a short literal such as 0.5 is exact), 0 if there is none.
int decimal_digits(const std::string& text) {
  int most = 0;
  for (const Decimal& d : decimals(text)) {
    size_t first = d.digits.find_first_not_of('0');
    int n = first == std::string::npos ? 1 : int(d.digits.size() - first);
    most = std::max(most, n);
  }
  return most;
}

// The name of the ERKN method an RKN table is the V -> 0 limit of, from its reference
// ("V -> 0 limit of NAME (...)"); empty for any other table.
std::string limit_parent(const generated::Table& t) {
  static const std::string prefix = "V -> 0 limit of ";
  std::string ref = t.reference;
  if (!t.rkn || ref.rfind(prefix, 0) != 0) return "";
  ref = ref.substr(prefix.size());
  return ref.substr(0, ref.find(" ("));
}

Method load(const generated::Table& t) {
  Method m;
  m.name = t.name, m.s = t.stages, m.order = t.order, m.rkn = t.rkn;
  m.names = coefficient_names(m.s);
  std::string all;
  for (int i = 0; i < m.s; ++i) {
    m.c.push_back(exact_number(parse(t.c_exact[i])));
    m.d.push_back(exact_number(parse(t.d_exact[i])));
    all += std::string(t.c_exact[i]) + " " + t.d_exact[i] + " ";
  }
  for (size_t k = 0; k < m.names.size(); ++k) {
    m.closed.push_back(t.closed_forms[k]);
    all += std::string(t.closed_forms[k]) + " ";
  }
  m.digits = decimal_digits(all);
  for (int k = 0; k < generated::kNumTables; ++k)
    if (limit_parent(generated::kTables[k]) == m.name) m.limit = generated::kTables[k].name;
  return m;
}
}  // namespace

std::vector<Method> erkn_methods() {
  std::vector<Method> out;
  for (int k = 0; k < generated::kNumTables; ++k)
    if (!generated::kTables[k].rkn && generated::kTables[k].modified == nullptr &&
        generated::kTables[k].pre_drift == nullptr)
      out.push_back(load(generated::kTables[k]));
  return out;
}

Method find_method(const std::string& name) {
  for (int k = 0; k < generated::kNumTables; ++k)
    if (name == generated::kTables[k].name) return load(generated::kTables[k]);
  throw std::invalid_argument("no method " + name);
}

std::vector<Method> paper_methods() {
  std::vector<Method> out;
  for (const PaperMethod& p : paper_series()) out.push_back(find_method(p.method));
  return out;
}

// ---------------------------------------------------------------------------------------------

namespace {
ex B(int i) { return sym("b" + std::to_string(i)); }
ex BB(int i) { return sym("bbar" + std::to_string(i)); }
ex A(int i, int j) { return sym(abar_name(i, j)); }
ex C(int i) { return sym("c" + std::to_string(i)); }
ex Dw(int i) { return sym("d" + std::to_string(i)); }
}  // namespace

std::vector<Condition> symplectic_conditions(const Method& m) {
  const ex v = vsym();
  std::vector<Condition> out;
  for (int i = 1; i <= m.s; ++i) {
    std::string I = std::to_string(i);
    out.push_back({"(g) line 1, i = " + I,
                   phi(0, v) * B(i) + v * phi(1, v) * BB(i) - Dw(i) * phi(0, pow(C(i), 2) * v),
                   kIdentity});
    out.push_back({"(g) line 2, i = " + I,
                   phi(1, v) * B(i) - phi(0, v) * BB(i) - C(i) * Dw(i) * phi(1, pow(C(i), 2) * v),
                   kIdentity});
  }
  for (int i = 1; i <= m.s; ++i)
    for (int j = 1; j < i; ++j)
      out.push_back({"(g) line 3, i = " + std::to_string(i) + ", j = " + std::to_string(j),
                     BB(j) * B(i) - BB(i) * B(j) - Dw(i) * A(i, j), kIdentity});
  return out;
}

ex tree_sum(const Method& m, const std::string& tree) {
  // tree: "b.e", "b.c", "b.c2", "b.c3", "b.Ae", "b.cAe", "b.Ac", "bbar.e", ..., "bbar.Ae".
  size_t dot = tree.find('.');
  std::string w = tree.substr(0, dot), t = tree.substr(dot + 1);
  ex sum = 0;
  for (int i = 1; i <= m.s; ++i) {
    ex weight = w == "b" ? B(i) : BB(i);
    ex row = 0, rowc = 0;
    for (int j = 1; j <= i; ++j) row += A(i, j), rowc += A(i, j) * C(j);
    ex phi_i;
    if (t == "e")
      phi_i = 1;
    else if (t == "c")
      phi_i = C(i);
    else if (t == "c2")
      phi_i = pow(C(i), 2);
    else if (t == "c3")
      phi_i = pow(C(i), 3);
    else if (t == "Ae")
      phi_i = row;
    else if (t == "cAe")
      phi_i = C(i) * row;
    else if (t == "Ac")
      phi_i = rowc;
    else
      throw std::invalid_argument("unknown tree " + tree);
    sum += weight * phi_i;
  }
  return sum;
}

namespace {
struct Tree {
  const char* name;  // weight.tree
  int rho;
  int factor;  // rho!/gamma
  int phi;     // phi index of the right-hand side
  numeric classical;
};
// Theorem 1, eq. (f), the SEN-trees up to order 4 with their rho!/gamma; the classical RKN
// right-hand sides (HNW Table II.14.3) are listed separately, not computed from the same numbers.
const std::vector<Tree>& trees() {
  static const std::vector<Tree> t = {
      {"b.e", 1, 1, 1, numeric(1)},         {"b.c", 2, 1, 2, numeric(1, 2)},
      {"b.c2", 3, 2, 3, numeric(1, 3)},     {"b.Ae", 3, 1, 3, numeric(1, 6)},
      {"b.c3", 4, 6, 4, numeric(1, 4)},     {"b.cAe", 4, 3, 4, numeric(1, 8)},
      {"b.Ac", 4, 1, 4, numeric(1, 24)},    {"bbar.e", 1, 1, 2, numeric(1, 2)},
      {"bbar.c", 2, 1, 3, numeric(1, 6)},   {"bbar.c2", 3, 2, 4, numeric(1, 12)},
      {"bbar.Ae", 3, 1, 4, numeric(1, 24)},
  };
  return t;
}
}  // namespace

std::vector<Condition> order_conditions(const Method& m) {
  const int r = m.order;
  std::vector<Condition> out;
  for (const Tree& t : trees()) {
    bool bbar = std::string(t.name).rfind("bbar", 0) == 0;
    // b: O(h^(r+1-rho)) -> V^k with 2k <= r - rho; bbar: O(h^(r-rho)) -> 2k <= r - rho - 1.
    int slack = bbar ? r - t.rho - 1 : r - t.rho;
    if (slack < 0) continue;
    // A tree with an abar-edge is a condition in two matrices (edge_failures); read with one V
    // it holds at V^0 only (beyond, the right-hand side is not rho!/gamma phi_rho(V)).
    if (std::string(t.name).find('A') != std::string::npos) slack = 0;
    std::string rhs =
        (t.factor == 1 ? "" : std::to_string(t.factor)) + "phi" + std::to_string(t.phi);
    out.push_back({std::string("(f) ") + t.name + " = " + rhs,
                   tree_sum(m, t.name) - t.factor * phi(t.phi, vsym()), slack / 2 + 1});
  }
  return out;
}

std::vector<Condition> classical_rkn_conditions(const Method& m) {
  std::vector<Condition> out;
  for (const Tree& t : trees()) {
    bool bbar = std::string(t.name).rfind("bbar", 0) == 0;
    if ((bbar ? m.order - 1 : m.order) < t.rho) continue;
    out.push_back({std::string("RKN ") + t.name + " = " + str(t.classical),
                   tree_sum(m, t.name) - t.classical, 1});
  }
  return out;
}

std::vector<EdgeTree> edge_trees() {
  return {{"b.Ae", false, 0, 0, 3},
          {"bbar.Ae", true, 0, 0, 3},
          {"b.cAe", false, 1, 0, 4},
          {"b.Ac", false, 0, 1, 4}};
}

Qs edge_weight(const EdgeTree& t, int j, int k) {
  // Edge: int_0^z (z-u) phi1((z-u)^2 W) u^q du, [W^k] = (-1)^k q! z^(2k+q+2) / (2k+q+2)!.
  // Root: int_0^1 phi0((1-z)^2 V) z^m dz, [V^j] = (-1)^j m! / (2j+m+1)!; bbar: (1-z) phi1(...),
  // (-1)^j m! / (2j+m+2)!. Here m = p + 2k + q + 2 with p the root's p-leaves.
  const int q = t.edge_leaves, m = t.root_leaves + 2 * k + q + 2;
  numeric w = factorial(numeric(q)) / factorial(numeric(2 * k + q + 2)) * factorial(numeric(m)) /
              factorial(numeric(2 * j + m + 1 + (t.bbar ? 1 : 0)));
  return Qs((j + k) % 2 ? -w : w);
}

std::vector<Failure> edge_failures(const Method& m, const std::vector<Series>& coefficients) {
  std::vector<Failure> out;
  auto at = [&](const std::string& name, int power) {
    const Series& x = coefficients.at(m.index(name));
    return power < int(x.size()) ? x[power] : Qs(0);
  };
  auto pow_c = [&](int i, int e) {
    Qs r(1);
    for (int n = 0; n < e; ++n) r = r * m.c[i];
    return r;
  };
  for (const EdgeTree& t : edge_trees()) {
    const int slack = m.order - t.rho - (t.bbar ? 1 : 0);  // 2(j + k) <= slack
    for (int n = 0; 2 * n <= slack; ++n)
      for (int j = 0; j <= n; ++j) {
        const int k = n - j;
        Qs sum(0);
        for (int i = 1; i <= m.s; ++i) {
          Qs edge(0);
          for (int l = 1; l <= i; ++l)
            edge = edge + at(abar_name(i, l), k) * pow_c(l - 1, t.edge_leaves);
          std::string w = (t.bbar ? "bbar" : "b") + std::to_string(i);
          sum = sum + at(w, j) * pow_c(i - 1, t.root_leaves) * edge;
        }
        Qs r = sum - edge_weight(t, j, k);
        if (!m.negligible(r))
          out.push_back({std::string("(f) ") + t.name + " at V^" + std::to_string(j) + " W^" +
                             std::to_string(k),
                         n, r.to_string()});
      }
  }
  return out;
}

std::vector<Condition> defining_conditions(const Method& m) {
  for (const PaperMethod& p : paper_series()) {
    if (m.name != p.method) continue;
    std::vector<Condition> out;
    for (const PaperDiagonal& c : p.diagonal) {
      std::string lhs = c.lhs;
      ex left = lhs.find('.') == std::string::npos ? parse(lhs) : tree_sum(m, lhs);
      out.push_back({c.name, left - parse(c.rhs), kIdentity});
    }
    return out;
  }
  throw std::invalid_argument("no defining conditions for " + m.name + ": not a paper method");
}

// ---------------------------------------------------------------------------------------------

Series eval_series(const ex& e, const Method& m, const std::vector<Series>& coefficients) {
  const int n = series_length(coefficients);
  if (is_a<numeric>(e)) return constant_series(Qs(ex_to<numeric>(e)), n);
  if (e == vsym()) {
    Series s(n, Qs(0));
    if (n > 1) s[1] = Qs(1);
    return s;
  }
  if (is_a<symbol>(e)) {
    std::string name = ex_to<symbol>(e).get_name();
    bool indexed = name.size() > 1 && name.find_first_not_of("0123456789", 1) == std::string::npos;
    if (indexed && name[0] == 'c') return constant_series(m.c.at(std::stoi(name.substr(1)) - 1), n);
    if (indexed && name[0] == 'd') return constant_series(m.d.at(std::stoi(name.substr(1)) - 1), n);
    Series s = coefficients.at(m.index(name));
    s.resize(n, Qs(0));
    return s;
  }
  if (is_a<GiNaC::add>(e)) {
    Series r = constant_series(Qs(0), n);
    for (size_t i = 0; i < e.nops(); ++i) r = add(r, eval_series(e.op(i), m, coefficients));
    return r;
  }
  if (is_a<GiNaC::mul>(e)) {
    Series r = constant_series(Qs(1), n);
    for (size_t i = 0; i < e.nops(); ++i) r = mul(r, eval_series(e.op(i), m, coefficients));
    return r;
  }
  if (is_a<GiNaC::power>(e) && is_a<numeric>(e.op(1)) && ex_to<numeric>(e.op(1)).is_integer()) {
    long k = ex_to<numeric>(e.op(1)).to_long();
    Series base = eval_series(e.op(0), m, coefficients);
    if (k < 0) base = inverse_series(base), k = -k;
    Series r = constant_series(Qs(1), n);
    for (long i = 0; i < k; ++i) r = mul(r, base);
    return r;
  }
  if (is_a<GiNaC::power>(e)) return constant_series(exact_number(e), n);
  if (is_ex_the_function(e, gen::phi)) {
    Series arg = eval_series(e.op(1), m, coefficients);
    for (int k = 0; k < n; ++k)
      if (k != 1 && !arg[k].is_zero()) throw std::invalid_argument("phi argument: " + str(e));
    return phi_series(ex_to<numeric>(e.op(0)).to_int(), n > 1 ? arg[1] : Qs(0), n);
  }
  throw std::invalid_argument("cannot evaluate as a series: " + str(e));
}

namespace {
const gen::TrigEnv& env_of(const Method& m) {
  static std::map<std::string, gen::TrigEnv> cache;
  std::string key = m.name;
  for (const std::string& c : m.closed) key += "|" + c;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  gen::TrigEnv env;
  for (int i = 0; i < m.s; ++i) {
    env[sym("c" + std::to_string(i + 1))] = gen::Rational{gen::TrigPoly(m.c[i])};
    env[sym("d" + std::to_string(i + 1))] = gen::Rational{gen::TrigPoly(m.d[i])};
  }
  for (size_t k = 0; k < m.names.size(); ++k)
    env[sym(m.names[k])] = gen::to_rational(parse(m.closed[k]), {}, vsym());
  return cache.emplace(key, env).first->second;
}
}  // namespace

gen::Rational exact(const ex& e, const Method& m) { return gen::to_rational(e, env_of(m), vsym()); }

bool identically_equal(const gen::Rational& x, const gen::Rational& y) {
  return (x.num * y.den - y.num * x.den).is_zero();
}

std::vector<Series> emitted_series(const Method& m, int n) {
  static std::map<std::string, std::vector<Series>> cache;
  std::string key = m.name + "#" + std::to_string(n);
  for (const std::string& c : m.closed) key += "|" + c;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  std::vector<Series> out;
  for (const std::string& c : m.closed) out.push_back(ginac_taylor(parse(c), n));
  return cache.emplace(key, out).first->second;
}

std::vector<Failure> series_failures(const std::vector<Condition>& conditions, const Method& m,
                                     const std::vector<Series>& coefficients) {
  std::vector<Failure> out;
  for (const Condition& c : conditions) {
    Series r = eval_series(c.residual, m, coefficients);
    int upto = std::min<int>(c.terms, int(r.size()));
    for (int k = 0; k < upto; ++k)
      if (!m.negligible(r[k])) {
        out.push_back({c.name, k, r[k].to_string()});
        break;
      }
  }
  return out;
}

std::vector<Failure> exact_failures(const std::vector<Condition>& conditions, const Method& m) {
  if (m.digits > 0) {
    // Decimal coefficients meet an identity only to their digits, and their frequencies
    // (1 - c_i)^2 are no squares of rationals, outside the trigonometric normal form: checked as
    // GiNaC series of the closed forms through V^7.
    std::vector<Condition> truncated = conditions;
    for (Condition& c : truncated) c.terms = std::min(c.terms, kDecimalIdentityTerms);
    return series_failures(truncated, m, emitted_series(m, kDecimalIdentityTerms));
  }
  std::vector<Failure> out;
  for (const Condition& c : conditions) {
    gen::Rational r = exact(c.residual, m);
    if (c.terms == kIdentity) {
      if (!r.num.is_zero()) out.push_back({c.name, -1, "not identically zero"});
      continue;
    }
    Series t = gen::taylor(r, c.terms);
    for (int k = 0; k < c.terms; ++k)
      if (!t[k].is_zero()) {
        out.push_back({c.name, k, t[k].to_string()});
        break;
      }
  }
  return out;
}

std::string to_string(const std::vector<Failure>& failures) {
  std::ostringstream os;
  for (const Failure& f : failures)
    os << "  " << f.condition << (f.power >= 0 ? " fails at V^" + std::to_string(f.power) : "")
       << ": " << f.value << "\n";
  return os.str();
}

std::vector<Series> printed_series(const Method& m) {
  for (const PaperMethod& p : paper_series()) {
    if (m.name != p.method) continue;
    std::vector<Series> out(m.names.size());
    std::vector<bool> seen(m.names.size(), false);
    for (const PaperCoefficient& c : p.coefficients) {
      int k = m.index(c.name);
      if (seen[k]) throw std::invalid_argument(m.name + ": " + c.name + " printed twice");
      seen[k] = true;
      for (const char* text : c.v) out[k].push_back(exact_number(parse(text)));
    }
    for (size_t k = 0; k < seen.size(); ++k)
      if (!seen[k]) throw std::invalid_argument(m.name + ": no printed series for " + m.names[k]);
    return out;
  }
  throw std::invalid_argument("the paper prints no series for " + m.name);
}

std::vector<Mismatch> paper_mismatches(const Method& m, const std::vector<Series>& derived) {
  std::vector<Series> printed = printed_series(m);
  std::vector<Mismatch> out;
  for (size_t k = 0; k < printed.size(); ++k)
    for (int p = 0; p < 4; ++p)
      if (!(printed[k][p] == derived.at(k).at(p)))
        out.push_back({m.name, m.names[k], p, printed[k][p], derived[k][p]});
  return out;
}

}  // namespace erkn::symtest
