// erkn-generate: derives every method of generator/methods.spec and writes generated/.
//   erkn-generate SPEC OUTDIR
#include <chrono>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "derive.hpp"
#include "emit.hpp"
#include "numerics.hpp"

int main(int argc, char** argv) {
  using namespace erkn::gen;
  if (argc != 3) {
    std::cerr << "usage: erkn-generate SPEC OUTDIR\n";
    return 2;
  }
  try {
    auto t0 = std::chrono::steady_clock::now();
    std::ifstream in(argv[1]);
    if (!in) throw std::runtime_error(std::string("cannot read ") + argv[1]);
    std::vector<Derived> out;
    for (const MethodSpec& spec : read_specs(in)) {
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
      out.push_back(std::move(m));
    }
    emit(out, argv[2], "cmake --build <build> --target regenerate");
    std::chrono::duration<double> dt = std::chrono::steady_clock::now() - t0;
    std::cerr << "erkn-generate: " << out.size() << " methods (and their RKN limits) in "
              << dt.count() << " s\n";
  } catch (const std::exception& e) {
    std::cerr << "erkn-generate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
