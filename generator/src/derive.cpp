#include "derive.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "cancel.hpp"
#include "phi.hpp"
#include "polish.hpp"

using namespace GiNaC;

namespace erkn::gen {
namespace {

// GiNaC prints sums and products in hash order, which changes from run to run (the hashes
// are seeded with addresses). Print with operands sorted instead, so output is reproducible.
std::string str(const ex& e) {
  auto wrap = [](const ex& x, const std::string& s) {
    return is_a<add>(x) || (is_a<numeric>(x) && !ex_to<numeric>(x).is_integer()) ||
                   (is_a<numeric>(x) && ex_to<numeric>(x).is_negative())
               ? "(" + s + ")"
               : s;
  };
  if (is_a<add>(e) || is_a<mul>(e)) {
    std::vector<std::string> parts;
    for (size_t i = 0; i < e.nops(); ++i)
      parts.push_back(is_a<mul>(e) ? wrap(e.op(i), str(e.op(i))) : str(e.op(i)));
    std::sort(parts.begin(), parts.end());
    std::string out;
    for (const std::string& p : parts)
      out += out.empty() ? p : (is_a<add>(e) ? (p[0] == '-' ? "" : "+") : "*") + p;
    return out;
  }
  if (is_a<GiNaC::power>(e)) return wrap(e.op(0), str(e.op(0))) + "^" + wrap(e.op(1), str(e.op(1)));
  if (is_a<function>(e)) {
    std::string out = ex_to<function>(e).get_name() + "(";
    for (size_t i = 0; i < e.nops(); ++i) out += (i ? "," : "") + str(e.op(i));
    return out + ")";
  }
  std::ostringstream os;
  os << e;
  return os.str();
}

// A solved quotient as "(num)/(den)", both expanded, with the sign that prints den smaller.
std::string quotient(const ex& e) {
  ex q = normal(e), n = expand(numer(q)), d = expand(denom(q));
  if (d == 1) return str(n);
  if (str(expand(-d)) < str(d)) n = expand(-n), d = expand(-d);
  return "(" + str(n) + ")/(" + str(d) + ")";
}

std::string idx(int i) { return std::to_string(i + 1); }

Rational constant(const Qs& q) { return {TrigPoly(q)}; }

Rational power(Rational r, int n) {
  if (n < 0) r = r.inverse(), n = -n;
  Rational out = constant(Qs(1));
  for (int k = 0; k < n; ++k) out = out * r;
  return out;
}

Rational convert(const ex& e, const TrigEnv& env, const symbol& v) {
  if (is_a<numeric>(e)) return constant(Qs(ex_to<numeric>(e)));
  if (e == v) return {TrigPoly::v()};
  if (auto it = env.find(e); it != env.end()) return it->second;
  if (is_a<add>(e)) {
    Rational r = constant(Qs(0));
    for (size_t i = 0; i < e.nops(); ++i) r = r + convert(e.op(i), env, v);
    return r;
  }
  if (is_a<mul>(e)) {
    Rational r = constant(Qs(1));
    for (size_t i = 0; i < e.nops(); ++i) r = r * convert(e.op(i), env, v);
    return r;
  }
  if (is_a<GiNaC::power>(e)) {
    if (is_a<numeric>(e.op(0)) && (e.op(1) == ex(1) / 2 || e.op(1) == ex(-1) / 2))
      return constant(Qs::from_ex(e));
    if (!is_a<numeric>(e.op(1)) || !ex_to<numeric>(e.op(1)).is_integer())
      throw std::runtime_error("not a rational function: " + str(e));
    return power(convert(e.op(0), env, v), ex_to<numeric>(e.op(1)).to_int());
  }
  if (is_ex_the_function(e, phi)) {
    // phi(j, w v) with w = omega^2 >= 0 in the field of the method.
    TrigPoly arg = convert(e.op(1), env, v).as_poly();
    Qs w = arg.is_zero() ? Qs(0) : arg.terms().begin()->second;
    if (!arg.is_zero() && !(arg.terms().size() == 1 && arg.terms().begin()->first.xpow == 2 &&
                            arg.terms().begin()->first.omega.is_zero()))
      throw std::runtime_error("phi argument is not a multiple of v: " + str(e));
    return phi_trig(ex_to<numeric>(e.op(0)).to_int(), w.sqrt());
  }
  throw std::runtime_error("cannot bring to trigonometric normal form: " + str(e));
}

/// Value of a constant expression: exact in Q(sqrt(s)) (numbers, sqrt(n), + * / and integer
/// powers), else approximate (Qs::approximate).
Qs value(const ex& e) {
  try {
    Rational r = convert(e, {}, symbol("unused"));
    TrigPoly p = r.as_poly();
    if (!p.is_constant()) throw std::runtime_error("not a constant: " + str(e));
    return p.is_zero() ? Qs(0) : p.terms().begin()->second;
  } catch (const std::exception&) {
    return Qs::from_ex(e);
  }
}

bool identically_zero(const Rational& r) { return r.num.is_zero(); }

/// A constant of the spec (c_i, d_i, a drift sum): GiNaC syntax read in Qs::kApproxDigits
/// digits, so decimals are exactly as written. Errors name the method and the coefficient.
Qs read_constant(const MethodSpec& spec, const std::string& what, const std::string& text) {
  long saved = GiNaC::Digits;
  GiNaC::Digits = Qs::kApproxDigits;
  try {
    symbol unused("v");
    ex e = make_parser(unused)(text);
    GiNaC::Digits = saved;
    return value(e);
  } catch (const std::exception& err) {
    GiNaC::Digits = saved;
    throw std::runtime_error(spec.name + ": " + what + " = '" + text + "': " + err.what());
  }
}

/// sqrt(r) for a rational r >= 0 as k sqrt(n)/m with n square-free (Qs expects a square-free n).
ex exact_sqrt(const numeric& r) {
  numeric n = r.numer() * r.denom(), k = 1;
  for (numeric f = 2; f * f <= n; f += 1)
    while (irem(n, f * f).is_zero()) n = n / (f * f), k *= f;
  return k * sqrt(ex(n)) / r.denom();
}

/// Real roots in Q(sqrt(n)) of a univariate polynomial over Q: those of its factors over Q of
/// degree 1 or 2 (a root of a higher factor is not in a quadratic field).
std::vector<ex> quadratic_roots(const ex& p, const symbol& x) {
  std::vector<ex> roots;
  ex f = factor(p);
  for (size_t i = 0; i < (is_a<mul>(f) ? f.nops() : 1); ++i) {
    ex g = is_a<mul>(f) ? f.op(i) : f;
    if (is_a<GiNaC::power>(g)) g = g.op(0);
    g = expand(g);
    ex a = g.coeff(x, 2), b = g.coeff(x, 1), c0 = g.coeff(x, 0);
    if (g.degree(x) == 1) roots.push_back(normal(-c0 / b));
    if (g.degree(x) != 2) continue;
    ex disc = expand(b * b - 4 * a * c0);
    if (!is_a<numeric>(disc) || ex_to<numeric>(disc).is_negative()) continue;
    for (int sign : {-1, 1})
      roots.push_back(expand((-b + sign * exact_sqrt(ex_to<numeric>(disc))) / (2 * a)));
  }
  return roots;
}

/// Two free nodes cu < cv (in the spec's order) from the two quadrature conditions p = q = 0
/// beyond the s that fix d: candidates are the roots of the resultants in each node, kept if both
/// conditions vanish exactly, the nodes are distinct from each other and from the given ones.
std::pair<ex, ex> two_free_nodes(const MethodSpec& spec, const ex& p, const ex& q, const symbol& cu,
                                 const symbol& cv, const exmap& given) {
  auto fail = [&](const std::string& why) { throw std::runtime_error(spec.name + ": " + why); };
  ex ru = resultant(p, q, cv), rv = resultant(p, q, cu);
  if (ru.is_zero() || rv.is_zero())
    fail("the quadrature conditions leave the free nodes " + str(cu) + ", " + str(cv) +
         " undetermined (a common factor): give one of them");
  std::vector<std::pair<ex, ex>> found;
  for (const ex& x : quadratic_roots(ru, cu))
    for (const ex& y : quadratic_roots(rv, cv)) {
      exmap at{{cu, x}, {cv, y}};
      if (!value(p.subs(at)).is_zero() || !value(q.subs(at)).is_zero()) continue;
      if (!(value(x) < value(y))) continue;  // the free nodes ascend in the spec's order
      bool distinct = true;
      for (const auto& [sym, val] : given)
        distinct = distinct && !value(val - x).is_zero() && !value(val - y).is_zero();
      if (distinct) found.emplace_back(x, y);
    }
  if (found.size() != 1)
    fail(std::to_string(found.size()) + " solutions for the free nodes " + str(cu) + " < " +
         str(cv) + " in a quadratic field (the roots of the resultants " + str(ru) + " and " +
         str(rv) + "): give one node");
  return found[0];
}

/// A decimal among the spec's nodes, drifts or weights: they get polished.
bool has_decimals(const MethodSpec& spec) {
  for (const auto* list :
       {&spec.c, &spec.d, &spec.e, &spec.pre_drift, &spec.pre_kick, &spec.pre_modified})
    for (const std::string& x : *list)
      if (x.find('.') != std::string::npos) return true;
  return false;
}

/// A processed method's pre-processor as given (pre_drift, pre_kick, pre_modified), into out.pre.
void take_processor(const MethodSpec& spec, Derived& out) {
  auto read = [&](const std::vector<std::string>& texts, const std::string& what) {
    std::vector<Qs> values;
    for (size_t k = 0; k < texts.size(); ++k)
      values.push_back(read_constant(spec, what + std::to_string(k + 1), texts[k]));
    return values;
  };
  out.pre = {read(spec.pre_drift, "pre_drift"), read(spec.pre_kick, "pre_kick"),
             read(spec.pre_modified, "pre_modified")};
}

/// Nodes and weights as given (every c_i and d_i, the e_i of modified kicks), into out; decimal
/// explicit methods polished onto the orders their digits meet.
void take_given_nodes(const MethodSpec& spec, exmap& nodes, const std::vector<symbol>& c,
                      Derived& out) {
  auto fail = [&](const std::string& why) { throw std::runtime_error(spec.name + ": " + why); };
  for (int i = 0; i < spec.stages; ++i) {
    out.c.push_back(value(nodes[c[i]]));
    out.d.push_back(read_constant(spec, "d" + idx(i), spec.d[i]));
    if (!spec.e.empty()) out.e.push_back(read_constant(spec, "e" + idx(i), spec.e[i]));
    // A pure modified kick (d_i = 0, e_i != 0, e.g. a corrector) is a stage of an explicit
    // method: its abar_ij are those of the splitting (derive()).
    const bool corrector = !spec.e.empty() && !out.e[i].is_zero();
    if (out.d[i].is_zero() && !corrector)
      fail("d" + idx(i) + " = 0: abar_ij = (...)/d_i is undefined");
  }
  if (has_decimals(spec) && spec.kind != SpecKind::explicit_erkn)
    out.node_derivation.push_back(
        "decimals read in " + std::to_string(Qs::kApproxDigits) +
        " digits, not polished (kind erkn): the certification judges them as given");
  take_processor(spec, out);
  if (has_decimals(spec) && spec.kind == SpecKind::explicit_erkn) {
    Polished p =
        polish_explicit(spec.name, out.c, out.d, out.e, spec.order, spec.generalized, out.pre);
    out.c = p.c, out.d = p.d, out.e = p.e, out.pre = p.pre, out.unmet_by_decimals = p.unmet;
    out.node_derivation.push_back(p.summary());
  }
}

/// The free nodes `?` (indices `unknown`, at most two) from the quadrature conditions beyond the
/// s that fixed d (quad[k] = sum_i d_i c_i^k - 1/(k+1), d = dsol), into `nodes`.
void solve_free_nodes(const MethodSpec& spec, const std::vector<symbol>& c,
                      const std::vector<ex>& quad, const ex& dsol, const std::vector<int>& unknown,
                      exmap& nodes, Derived& out) {
  auto fail = [&](const std::string& why) { throw std::runtime_error(spec.name + ": " + why); };
  const int s = spec.stages, nfree = int(unknown.size());
  if (nfree > 2)
    fail(std::to_string(nfree) + " free nodes: the generator solves at most two (give the others)");
  if (nfree == 2) {  // two polynomial conditions beyond the s that fixed d
    if (int(quad.size()) < s + 2)
      fail("2 free nodes need the quadrature conditions k = " + std::to_string(s) + ", " +
           std::to_string(s + 1) + " beyond the s that fix d, i.e. order >= " +
           std::to_string(s + 2) + " (claimed " + std::to_string(spec.order) + "): give one node");
    const symbol &cu = c[unknown[0]], &cv = c[unknown[1]];
    ex p = expand(normal(quad[s].subs(dsol).subs(nodes)).numer());
    ex q = expand(normal(quad[s + 1].subs(dsol).subs(nodes)).numer());
    auto [x, y] = two_free_nodes(spec, p, q, cu, cv, nodes);
    out.node_derivation.push_back(str(cu) + ", " + str(cv) + " = " + str(x) + ", " + str(y) +
                                  " (quadrature conditions k = " + std::to_string(s) + ", " +
                                  std::to_string(s + 1) + ")");
    nodes[cu] = x, nodes[cv] = y;
  } else if (nfree == 1) {  // the first condition beyond the s that fixed d fixes the node
    if (spec.order <= s) fail("no condition left to fix c" + idx(unknown[0]));
    const symbol& cu = c[unknown[0]];
    ex p = expand(normal(quad[s].subs(dsol)).numer());
    if (p.degree(cu) != 1) fail("the node condition is not linear in c" + idx(unknown[0]));
    ex sol = normal(-p.coeff(cu, 0) / p.coeff(cu, 1));
    out.node_derivation.push_back(str(cu) + " = " + quotient(sol));
    nodes[cu] = sol.subs(nodes);
  }
}

/// Nodes c_i and weights d_i (into out.c, out.d): as given, or the d_i from the quadrature
/// conditions sum_i d_i c_i^k = 1/(k+1), k < s (eq. (f) for the bushy trees at V = 0, over
/// symbolic c_i so the general formulas appear), and one or two nodes `?` from the next ones.
void solve_nodes(const MethodSpec& spec, const std::vector<symbol>& c, const std::vector<symbol>& d,
                 Derived& out) {
  const int s = spec.stages;
  auto fail = [&](const std::string& why) { throw std::runtime_error(spec.name + ": " + why); };
  exmap nodes;
  std::vector<int> unknown;
  for (int i = 0; i < s; ++i) {
    if (spec.c[i] == "?")
      unknown.push_back(i);
    else
      nodes[c[i]] = read_constant(spec, "c" + idx(i), spec.c[i]).to_ex();
  }
  if (!spec.d.empty()) {
    if (!unknown.empty()) fail("c" + idx(unknown[0]) + " = ?: with d given, give every c_i");
    return take_given_nodes(spec, nodes, c, out);
  }
  std::vector<ex> quad;  // sum_i d_i c_i^k - 1/(k+1), k = 0 .. s (as far as the order goes)
  const int nfree = int(unknown.size());
  for (int k = 0; k < std::min(spec.order, s + std::max(1, nfree)); ++k) {
    ex sum = 0;
    for (int i = 0; i < s; ++i) sum += d[i] * pow(c[i], k);
    quad.push_back(sum - numeric(1, k + 1));
  }
  if (int(quad.size()) < s) fail("order < stages leaves d underdetermined: give d");
  lst deqs, dsyms;
  for (int i = 0; i < s; ++i) deqs.append(quad[i] == 0), dsyms.append(d[i]);
  const ex dsol = lsolve(deqs, dsyms);
  solve_free_nodes(spec, c, quad, dsol, unknown, nodes, out);
  for (size_t i = 0; i < dsol.nops(); ++i)
    out.node_derivation.push_back(str(dsol.op(i).op(0)) + " = " + quotient(dsol.op(i).op(1)));
  for (int i = 0; i < s; ++i) out.c.push_back(value(nodes[c[i]].subs(nodes)));
  exmap cd;  // c_i -> values
  for (int i = 0; i < s; ++i) cd[c[i]] = out.c[i].to_ex();
  for (int i = 0; i < s; ++i) {
    out.d.push_back(value(ex(d[i]).subs(dsol).subs(cd)));
    if (out.d[i].is_zero()) fail("d" + idx(i) + " = 0: abar_ij = (...)/d_i is undefined");
  }
}

/// The s+1 drifts of a splitting method sum to 1: exactly, or to 1e-12 for decimals (a
/// transcription check; the polishing makes the decimals consistent).
void check_drift_sum(const MethodSpec& spec) {
  if (spec.drift_sum.empty()) return;
  Qs sum = read_constant(spec, "the sum of the drifts", spec.drift_sum), err = sum - Qs(1);
  if (err.is_zero() || (sum.is_approx() && std::abs(err.to_double()) <= 1e-12)) return;
  throw std::runtime_error(spec.name + ": the drifts sum to " + sum.to_string() + ", not 1");
}

/// Every decimal literal of `text` written as the exact rational it denotes, "0.25" ->
/// "(25/10^2)": GiNaC's parser would read it as a float of GiNaC::Digits digits.
std::string exact_decimals(const std::string& text) {
  static const std::regex decimal(R"((^|[^A-Za-z0-9_.])([0-9]*)\.([0-9]+)([eE]([-+]?[0-9]+))?)");
  std::string out;
  auto last = text.cbegin();
  for (std::sregex_iterator it(text.begin(), text.end(), decimal), end; it != end; ++it) {
    const std::smatch& m = *it;
    const std::string digits = m[2].str() + m[3].str();
    const long exponent = long(m[3].length()) - (m[5].matched ? std::stol(m[5].str()) : 0);
    out.append(last, m[0].first).append(m[1].str());
    out += "(" + (digits.empty() ? "0" : digits) + "/10^(" + std::to_string(exponent) + "))";
    last = m[0].second;
  }
  return out.append(last, text.cend());
}

/// The tableau's symbols over v (b_i, bbar_i, abar_ij beside the c_i, d_i of solve_nodes), the
/// trig environment that gives them meaning, and `record`, which stores a solved coefficient.
struct Tableau {
  Tableau(const MethodSpec& spec, Derived& out, std::vector<symbol> c0, std::vector<symbol> d0);
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error(spec.name + ": " + why);
  }
  Rational trig(const ex& e) const { return to_rational(e, env, v); }
  /// `shown` is the solution as derivation.md prints it (the symbols phi0V... spelled out).
  void record(int index, const symbol& sym, const ex& solution, const ex& shown);

  const MethodSpec& spec;
  Derived& out;
  const int s;
  std::vector<symbol> c, d;
  symbol v{"v"};  // (created after c, d and the nodes' symbols: GiNaC orders terms by creation)
  std::vector<symbol> b, bb;
  std::vector<std::vector<symbol>> a;
  TrigEnv env;
};

Tableau::Tableau(const MethodSpec& spec, Derived& out, std::vector<symbol> c0,
                 std::vector<symbol> d0)
    : spec(spec), out(out), s(spec.stages), c(std::move(c0)), d(std::move(d0)), a(s) {
  for (int i = 0; i < s; ++i) {
    b.emplace_back("b" + idx(i)), bb.emplace_back("bbar" + idx(i));
    for (int j = 0; j <= i; ++j) a[i].emplace_back("abar" + idx(i) + idx(j));
  }
  for (int i = 0; i < s; ++i) env[c[i]] = constant(out.c[i]), env[d[i]] = constant(out.d[i]);
  out.coefficients.resize(2 * s + s * (s + 1) / 2);
}

void Tableau::record(int index, const symbol& sym, const ex& solution, const ex& shown) {
  Rational r = cancel_common(trig(solution));
  Coefficient& k = out.coefficients[index];
  k.name = str(sym);
  k.closed_form = r.is_poly() ? Rational{r.as_poly()} : r.monic();
  k.derivation = str(sym) + " = " + quotient(shown);
  env[sym] = k.closed_form;
}

/// abar_ii from the spec's `diagonal` equations, taken as equalities in V; in them bAe, bbarAe,
/// bcAe, bAc stand for the tree sums of eq. (f) with abar(V). Returns the equations lhs - rhs.
std::vector<ex> solve_diagonal(Tableau& t) {
  const MethodSpec& spec = t.spec;
  const std::vector<symbol>&b = t.b, &bb = t.bb, &c = t.c;
  const std::vector<std::vector<symbol>>& a = t.a;
  const symbol& v = t.v;
  const int s = spec.stages;
  auto fail = [&](const std::string& why) { throw std::runtime_error(spec.name + ": " + why); };
  symtab table;
  table["v"] = v;
  ex bAe = 0, bbarAe = 0, bcAe = 0, bAc = 0;
  for (int i = 0; i < s; ++i) {
    ex row = 0, rowc = 0;
    for (int j = 0; j <= i; ++j) row += a[i][j], rowc += a[i][j] * c[j];
    bAe += b[i] * row, bbarAe += bb[i] * row, bcAe += b[i] * c[i] * row, bAc += b[i] * rowc;
    table["b" + idx(i)] = b[i], table["bbar" + idx(i)] = bb[i], table["c" + idx(i)] = c[i];
    for (int j = 0; j <= i; ++j) table["abar" + idx(i) + idx(j)] = a[i][j];
  }
  table["bAe"] = bAe, table["bbarAe"] = bbarAe, table["bcAe"] = bcAe, table["bAc"] = bAc;
  parser read(table, true);
  lst diag_eqs, diag_syms;
  std::vector<ex> diagonal;
  for (const std::string& text : spec.diagonal) {
    size_t eqpos = text.find("==");
    if (eqpos == std::string::npos) fail("diagonal condition is not an equation: " + text);
    ex lhs = read(exact_decimals(text.substr(0, eqpos))),
       rhs = read(exact_decimals(text.substr(eqpos + 2)));
    diag_eqs.append(lhs == rhs);
    diagonal.push_back(lhs - rhs);
  }
  for (int i = 0; i < s; ++i) diag_syms.append(a[i][i]);
  if (diag_eqs.nops() != size_t(s)) fail("need one diagonal equation per stage");
  ex dsol2 = lsolve(diag_eqs, diag_syms);
  if (dsol2.nops() != size_t(s)) fail("diagonal equations do not determine abar_ii");
  for (int i = 0; i < s; ++i) {
    ex solution = normal(ex(a[i][i]).subs(dsol2));
    t.record(abar_index(s, i + 1, i + 1), a[i][i], solution, solution);
  }

  return diagonal;
}

}  // namespace

Rational to_rational(const ex& e, const TrigEnv& env, const symbol& v) {
  // One numer_denom(): numer() and denom() would each normalise anew and may scale the two
  // parts by constants of opposite sign.
  ex nd = normal(e).numer_denom();
  Rational num = convert(nd.op(0), env, v), den = convert(nd.op(1), env, v);
  return {num.num * den.den, num.den * den.num};
}

namespace {

/// b_i, bbar_i: the first two symplectic conditions of (g), a 2x2 linear system per stage.
void solve_b_bbar(Tableau& t) {
  symbol p0("phi0V"), p1("phi1V"), q0("phi0c2V"), q1("phi1c2V");
  for (int i = 0; i < t.s; ++i) {
    const symbol &b = t.b[i], &bb = t.bb[i], &c = t.c[i], &v = t.v;
    lst eqs{p0 * b + v * p1 * bb == t.d[i] * q0, p1 * b - p0 * bb == c * t.d[i] * q1};
    ex sol = lsolve(eqs, lst{b, bb});
    exmap phis{
        {p0, phi(0, v)}, {p1, phi(1, v)}, {q0, phi(0, pow(c, 2) * v)}, {q1, phi(1, pow(c, 2) * v)}};
    t.env[p0] = {TrigPoly::phi0(Qs(1))}, t.env[p1] = {TrigPoly::phi1(Qs(1))};
    t.env[q0] = {TrigPoly::phi0(t.out.c[i])}, t.env[q1] = {TrigPoly::phi1(t.out.c[i])};
    for (int k = 0; k < 2; ++k) {
      const symbol& sym = k == 0 ? b : bb;
      const int index = k == 0 ? i : t.s + i;
      ex solution = normal(ex(sym).subs(sol));
      t.record(index, sym, solution, solution.subs(phis));
      if (!t.out.coefficients[index].closed_form.is_poly())
        t.fail("symplectic solution for " + str(sym) + " did not reduce to a trig polynomial");
    }
  }
}

/// abar_ij, j < i: the third symplectic condition of (g) (j < i; the paper prints j <= i). At a
/// pure modified kick (d_i = 0) it reads 0 = 0: the splitting's abar_ij instead.
void solve_abar(Tableau& t) {
  for (int i = 0; i < t.s; ++i)
    for (int j = 0; j < i; ++j) {
      const int index = abar_index(t.s, i + 1, j + 1);
      const symbol &ci = t.c[i], &cj = t.c[j];
      if (t.out.d[i].is_zero()) {
        const std::string I = idx(i), J = idx(j);
        t.record(index, t.a[i][j], t.d[j] * (ci - cj) * phi(1, pow(ci - cj, 2) * t.v), 0);
        // Written out: GiNaC prints (c_i - c_j)^2 with either sign first, run to run.
        t.out.coefficients[index].derivation = "abar" + I + J + " = d" + J + "*(c" + I + "-c" + J +
                                               ")*phi(1,(c" + I + "-c" + J + ")^2*v)";
        continue;
      }
      ex sol =
          lsolve(lst{t.bb[j] * t.b[i] - t.bb[i] * t.b[j] == t.d[i] * t.a[i][j]}, lst{t.a[i][j]});
      ex solution = normal(ex(t.a[i][j]).subs(sol));
      t.record(index, t.a[i][j], solution, solution);
    }
}

/// Everything imposed holds identically in V: (g) 1-3 and the spec's diagonal equations.
void verify(const Tableau& t, const std::vector<ex>& diagonal) {
  const symbol& v = t.v;
  for (int i = 0; i < t.s; ++i) {
    const symbol &b = t.b[i], &bb = t.bb[i], &c = t.c[i], &d = t.d[i];
    ex g1 = phi(0, v) * b + v * phi(1, v) * bb - d * phi(0, pow(c, 2) * v);
    ex g2 = phi(1, v) * b - phi(0, v) * bb - c * d * phi(1, pow(c, 2) * v);
    if (!identically_zero(t.trig(g1)) || !identically_zero(t.trig(g2)))
      t.fail("symplectic condition (g) 1-2 fails at stage " + idx(i));
    for (int j = 0; j < i; ++j)
      if (!identically_zero(t.trig(t.bb[j] * b - bb * t.b[j] - d * t.a[i][j])))
        t.fail("symplectic condition (g) 3 fails for i=" + idx(i) + ", j=" + idx(j));
  }
  for (size_t k = 0; k < diagonal.size(); ++k)
    if (!identically_zero(t.trig(diagonal[k])))
      t.fail("diagonal condition '" + t.spec.diagonal[k] + "' fails");
}

}  // namespace

Derived derive(const MethodSpec& spec) {
  Derived out;
  out.spec = spec;
  // Nodes and weights: given, or from the quadrature conditions at V = 0.
  std::vector<symbol> c, d;
  for (int i = 0; i < spec.stages; ++i) c.emplace_back("c" + idx(i)), d.emplace_back("d" + idx(i));
  solve_nodes(spec, c, d, out);
  check_drift_sum(spec);
  Tableau t(spec, out, std::move(c), std::move(d));
  solve_b_bbar(t);
  solve_abar(t);
  // abar_ii: zero (explicit), or the diagonal equations of the spec as equalities in V.
  std::vector<ex> diagonal;
  if (spec.kind == SpecKind::explicit_erkn)
    for (int i = 0; i < t.s; ++i) t.record(abar_index(t.s, i + 1, i + 1), t.a[i][i], 0, 0);
  else
    diagonal = solve_diagonal(t);
  verify(t, diagonal);
  for (Coefficient& k : out.coefficients) k.series = taylor(k.closed_form, kSeriesTerms);
  auto t0 = std::chrono::steady_clock::now();
  certify_order(out);
  out.certify_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

namespace {

// The first failing condition of a tree with K f-vertices, as text.
std::string generalized_failure(const Certificate& cert, int K) {
  for (const CheckedCondition& c : cert.checked)
    if (!c.holds && cert.trees[c.condition.tree].fvertices == K)
      return "tree " + cert.trees[c.condition.tree].name + ": condition " +
             c.condition.text(cert.trees) + " has residual " + c.residual;
  return "no failing condition";
}

// Refuses (throws) a certificate below the spec's claims, naming the first failing tree.
void check_claim(const Derived& m, const Certificate& cert, bool rkn, const std::string& unmet) {
  const std::string what = m.pre.empty() ? "" : " (of pi o K o pi^-1, the processed method)";
  for (size_t K = 0; !rkn && K < m.spec.generalized.size(); ++K)
    if (K >= cert.generalized.size() || cert.generalized[K] < m.spec.generalized[K])
      throw std::runtime_error(
          m.spec.name + ": claimed generalized order " + std::to_string(m.spec.generalized[K]) +
          " for eps^" + std::to_string(K + 1) + what + " is not certified (" +
          (K < cert.generalized.size() ? std::to_string(cert.generalized[K]) : "unchecked") +
          "): " + generalized_failure(cert, int(K) + 1) + unmet);
  if (cert.order < m.spec.order) {
    const CheckedCondition* f = cert.first_failure();
    throw std::runtime_error(
        (rkn ? m.spec.rkn + " (the V -> 0 limit of " + m.spec.name + ")" : m.spec.name) +
        ": claimed order " + std::to_string(m.spec.order) + what + " fails at tree " +
        cert.trees[f->condition.tree].name + ": condition " + f->condition.text(cert.trees) +
        " has residual " + f->residual + " (certified order " + std::to_string(cert.order) + ")" +
        unmet);
  }
}

}  // namespace

void certify_order(Derived& m) {
  const int s = m.stages();
  SeriesTableau t;
  t.s = s;
  t.c = m.c;
  const std::vector<Coefficient>& k = m.coefficients;
  for (int i = 0; i < s; ++i) t.b.push_back(k[i].series), t.bbar.push_back(k[s + i].series);
  for (int i = 0; i < s; ++i)
    for (int j = 0; j <= i; ++j) t.abar.push_back(k[abar_index(s, i + 1, j + 1)].series);
  // Modified kicks: the splitting's kernels with -2 e_i in place of d_i (explicit methods only).
  const SeriesTableau mod = explicit_series(m.c, m.d, kSeriesTerms, m.e);
  t.b_mod = mod.b_mod, t.bbar_mod = mod.bbar_mod, t.abar_mod = mod.abar_mod;
  int max_power = std::max(m.spec.order + 1, kCertifyPowers);
  for (int g : m.spec.generalized) max_power = std::max(max_power, g + 1);
  const std::string unmet = m.unmet_by_decimals == 0
                                ? ""
                                : "; the decimals do not meet the claim (polished onto the orders "
                                  "they meet, " +
                                      std::to_string(m.unmet_by_decimals) +
                                      " conditions left out): a wrong claim or a transcription "
                                      "error";
  for (bool rkn : {false, true}) {
    if (rkn && m.spec.rkn.empty()) continue;
    Certificate cert = certify(t, rkn, max_power);
    if (!rkn && !m.pre.empty()) {  // the kernel's own order; the claims are psi's
      m.kernel_certificate = std::move(cert);
      const KickSequence psi = composition(m.c, m.d, m.e, m.pre);
      cert = certify(explicit_series(psi.c, psi.d, max_power / 2 + 1, psi.e), false, max_power);
    }
    check_claim(m, cert, rkn, unmet);
    (rkn ? m.rkn_certificate : m.certificate) = std::move(cert);
  }
}

}  // namespace erkn::gen
