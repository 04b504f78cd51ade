#include "spec.hpp"

#include <sstream>
#include <stdexcept>

namespace erkn::gen {
namespace {

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);) out.push_back(trim(item));
  return out;
}

// `drift a_1, ..., a_s[, a_(s+1)]`: the drifts of a splitting method, c_i = a_1 + ... + a_i.
std::vector<std::string> nodes_from_drifts(const std::vector<std::string>& drifts) {
  std::vector<std::string> c;
  std::string sum;
  for (const std::string& a : drifts)
    c.push_back(sum += (sum.empty() ? "" : "+") + ("(" + a + ")"));
  return c;
}

// A processor (pre_drift, pre_kick, pre_modified) needs an explicit kernel with its kicks given.
template <class Fail>
void check_processor(const MethodSpec& m, Fail fail) {
  if (!m.processed() && m.pre_drift.empty() && m.pre_modified.empty()) return;
  if (!m.processed()) fail("a processor needs `pre_kick`");
  const size_t k = m.pre_kick.size();
  if (m.pre_drift.size() != k && m.pre_drift.size() != k + 1)
    fail("`pre_drift` needs one drift before each of the " + std::to_string(k) +
         " `pre_kick` (and optionally one after the last)");
  if (!m.pre_modified.empty() && m.pre_modified.size() != k)
    fail("`pre_modified` needs one coefficient per `pre_kick`");
  if (m.kind != SpecKind::explicit_erkn || m.d.empty())
    fail("a processor needs kind explicit with the kernel's kicks d given");
  if (!m.rkn.empty()) fail("no `rkn` limit for a processed method");
}

void check(const MethodSpec& m) {
  auto fail = [&](const std::string& why) {
    throw std::runtime_error("methods.spec:" + std::to_string(m.line) + ": method " + m.name +
                             ": " + why);
  };
  if (m.stages < 1) fail("needs `stages` >= 1");
  if (m.order < 1) fail("needs the claimed `order` >= 1");
  if (int(m.c.size()) != m.stages) fail("needs one c (or drift) per stage");
  if (!m.d.empty() && int(m.d.size()) != m.stages) fail("needs one d (kick) per stage");
  if (m.kind == SpecKind::erkn && m.diagonal.empty()) fail("kind erkn needs `diagonal`");
  if (m.kind == SpecKind::explicit_erkn && !m.diagonal.empty())
    fail("kind explicit has abar_ii = 0: no `diagonal`");
  if (m.kind == SpecKind::erkn && m.rkn.empty()) fail("kind erkn needs the `rkn` name");
  if (m.source.empty()) fail("needs a `source`");
  check_processor(m, fail);
  if (m.e.empty()) return;
  if (int(m.e.size()) != m.stages) fail("needs one modified-kick coefficient per stage");
  if (m.kind != SpecKind::explicit_erkn)
    fail(
        "`modified` is for kind explicit (an implicit stage would need the third derivatives of "
        "U)");
  if (m.d.empty()) fail("`modified` needs the kicks d given");
  if (!m.rkn.empty())
    fail("no `rkn` limit with modified kicks (it would need grad(|Mq + grad U|^2))");
}

}  // namespace

std::string identifier(const std::string& name) {
  std::string id;
  for (char ch : name)
    if (ch == '(' || ch == ',' || ch == '-' || ch == '.' || ch == ' ')
      id += '_';
    else if (ch != ')')
      id += ch;
  return id;
}

namespace {

// Sets one `key value` line's field of m; false for an unknown key.
bool set_field(MethodSpec& m, const std::string& key, const std::string& value) {
  if (key == "rkn") {
    m.rkn = value;
  } else if (key == "source" || key == "section") {
    m.source = value;
    m.paper = key == "section";
  } else if (key == "stages") {
    m.stages = std::stoi(value);
  } else if (key == "order") {
    m.order = std::stoi(value);
  } else if (key == "generalized") {
    for (const std::string& g : split(value, ',')) m.generalized.push_back(std::stoi(g));
  } else if (key == "c") {
    m.c = split(value, ',');
  } else if (key == "drift") {
    m.drift = split(value, ',');
  } else if (key == "d" || key == "kick") {
    m.d = split(value, ',');
  } else if (key == "modified") {
    m.e = split(value, ',');
  } else if (key == "pre_drift") {
    m.pre_drift = split(value, ',');
  } else if (key == "pre_kick") {
    m.pre_kick = split(value, ',');
  } else if (key == "pre_modified") {
    m.pre_modified = split(value, ',');
  } else if (key == "diagonal") {
    m.diagonal = split(value, ';');
  } else {
    return false;
  }
  return true;
}

// Nodes from drifts (the last drift closes the step), then the spec's consistency checks.
void finish(MethodSpec& m) {
  if (!m.drift.empty() && !m.c.empty()) throw std::runtime_error(m.name + ": c or drift, not both");
  if (!m.drift.empty()) m.c = nodes_from_drifts(m.drift);
  if (!m.drift.empty() && int(m.c.size()) == m.stages + 1) {
    m.drift_sum = m.c.back();
    m.c.pop_back();
  }
  check(m);
}

}  // namespace

std::vector<MethodSpec> read_specs(std::istream& in) {
  std::vector<MethodSpec> specs;
  int lineno = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineno;
    line = trim(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    size_t sp = line.find_first_of(" \t");
    std::string key = line.substr(0, sp),
                value = sp == std::string::npos ? "" : trim(line.substr(sp));
    auto fail = [&](const std::string& why) {
      throw std::runtime_error("methods.spec:" + std::to_string(lineno) + ": " + why);
    };
    if (key == "method") {
      specs.push_back({});
      specs.back().name = value;
      specs.back().line = lineno;
      continue;
    }
    if (specs.empty()) fail("'" + key + "' before the first 'method'");
    MethodSpec& m = specs.back();
    if (key == "kind") {
      if (value != "erkn" && value != "explicit") fail("kind is erkn or explicit, not " + value);
      m.kind = value == "erkn" ? SpecKind::erkn : SpecKind::explicit_erkn;
    } else if (!set_field(m, key, value)) {
      fail("unknown key '" + key + "'");
    }
  }
  for (MethodSpec& m : specs) finish(m);
  return specs;
}

}  // namespace erkn::gen
