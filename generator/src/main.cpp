// erkn-generate: derives and certifies methods from spec files (the language is documented at
// the top of generator/methods.spec and in docs/user-methods.md).
//   erkn-generate SPEC OUTDIR                 erkn's own generated/ (methods.def, tables)
//   erkn-generate SPEC... --out DIR [--json]  a user's methods: DIR/erkn_methods.cpp (compiled
//                                             into a program, erkn_add_methods), DIR/derivation.md,
//                                             and with --json DIR/methods.json (Method::load)
// A spec whose claimed order is not certified is refused: exit status 1, the method and the
// first failing tree on stderr.
#include <chrono>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "derive.hpp"
#include "emit.hpp"
#include "numerics.hpp"

namespace {

using namespace erkn::gen;

struct Arguments {
  std::vector<std::string> specs;
  std::string out;  // --out DIR: a user's methods
  bool json = false;
  bool help = false;
  std::string legacy_dir;  // SPEC OUTDIR
};

constexpr const char* kUsage =
    "usage: erkn-generate SPEC OUTDIR | erkn-generate SPEC... --out DIR [--json]\n";

constexpr const char* kHelp =
    "Derives the methods of each SPEC file (the spec language: docs/user-methods.md), certifies\n"
    "their claimed orders from the SEN-trees and polishes their coefficients.\n"
    "  SPEC... --out DIR  writes DIR/erkn_methods.cpp (compile it into a program, as\n"
    "                     erkn_add_methods does) and DIR/derivation.md\n"
    "  --json             also writes DIR/methods.json (erkn::Method::load, erkn.load_methods)\n"
    "  SPEC OUTDIR        erkn's own generated/ tables (the regenerate target)\n"
    "  --help             this text\n"
    "Exit status: 0 done, 1 a spec refused (the method and the first failing tree are named),\n"
    "2 a usage error.\n";

Arguments parse(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h")
      a.help = true;
    else if (arg == "--out" && i + 1 < argc)
      a.out = argv[++i];
    else if (arg == "--json")
      a.json = true;
    else if (arg.starts_with("--"))
      throw std::invalid_argument("unknown option " + arg);
    else
      a.specs.push_back(arg);
  }
  if (a.help) return a;
  if (a.out.empty() && a.specs.size() == 2 && !a.json)
    a.legacy_dir = a.specs.back(), a.specs.pop_back();
  if (a.specs.empty() || (a.out.empty() && a.legacy_dir.empty()))
    throw std::invalid_argument("usage");
  return a;
}

Derived derive_certified(const MethodSpec& spec) {
  Derived m = derive(spec);
  for (Coefficient& k : m.coefficients) {
    try {
      locate_poles(k);
    } catch (const std::exception& err) {  // name the method and the coefficient
      throw std::runtime_error(spec.name + ": " + k.name + ": " + err.what());
    }
  }
  std::cerr << "derived " << spec.name << ": order " << m.certificate.order << " certified ("
            << m.certificate.checked.size() << " conditions, " << m.certify_seconds << " s)\n";
  return m;
}

std::vector<Derived> derive_all(const std::vector<std::string>& files) {
  std::vector<Derived> out;
  for (const std::string& file : files) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file);
    std::vector<MethodSpec> specs;
    try {
      specs = read_specs(in);
    } catch (const std::exception& e) {
      throw std::runtime_error(file + ": " + e.what());
    }
    for (const MethodSpec& spec : specs) out.push_back(derive_certified(spec));
  }
  return out;
}

std::string joined(const std::vector<std::string>& xs) {
  std::string out;
  for (const std::string& x : xs) out += (out.empty() ? "" : " ") + x;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Arguments a = parse(argc, argv);
    if (a.help) {
      std::cout << kUsage << kHelp;
      return 0;
    }
    auto t0 = std::chrono::steady_clock::now();
    const std::vector<Derived> out = derive_all(a.specs);
    if (!a.legacy_dir.empty()) {
      emit(out, a.legacy_dir, "cmake --build <build> --target regenerate");
    } else {
      const std::string command = "erkn-generate " + joined(a.specs) + " --out " + a.out;
      emit_user(out, a.out, command, joined(a.specs));
      if (a.json) {
        std::ofstream f(a.out + "/methods.json", std::ios::binary);
        if (!(f << methods_json(out))) throw std::runtime_error("cannot write methods.json");
      }
    }
    std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
    std::cerr << "erkn-generate: " << out.size() << " methods (and their RKN limits) in "
              << dt.count() << " s\n";
  } catch (const std::invalid_argument& e) {
    std::cerr << "erkn-generate: "
              << (std::string(e.what()) == "usage" ? "" : e.what() + std::string("\n")) << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "erkn-generate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
