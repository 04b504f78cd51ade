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

}  // namespace

std::string identifier(const std::string& name) {
  std::string id;
  for (char ch : name)
    if (ch == '(')
      id += '_';
    else if (ch != ')')
      id += ch;
  return id;
}

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
      continue;
    }
    if (specs.empty()) fail("'" + key + "' before the first 'method'");
    MethodSpec& m = specs.back();
    if (key == "rkn")
      m.rkn = value;
    else if (key == "section")
      m.section = value;
    else if (key == "stages")
      m.stages = std::stoi(value);
    else if (key == "order")
      m.order = std::stoi(value);
    else if (key == "c")
      m.c = split(value, ',');
    else if (key == "diagonal")
      m.diagonal = split(value, ';');
    else
      fail("unknown key '" + key + "'");
  }
  for (const MethodSpec& m : specs)
    if (m.stages < 1 || m.order < 1 || int(m.c.size()) != m.stages || m.rkn.empty() ||
        m.diagonal.empty())
      throw std::runtime_error("methods.spec: method " + m.name +
                               " needs rkn, stages, order, one c per stage and diagonal");
  return specs;
}

}  // namespace erkn::gen
