// erkn: the command-line face of the library.
//   erkn list [--json]             every method: kind, stages, certified order, source
// Every command takes --methods-file F.json (erkn-generate --json): a user's methods join the
// registry (erkn run hands it to erkn-experiments).
//   erkn tableau NAME ...          coefficients at a v, Taylor series, or poles (JSON)
//   erkn run ...                   the paper's problems against peers: charts, docs/results.md
//   erkn stability NAME|all ...    stability regions of S(V, z) (CSV and charts)
//   erkn advise NAME --h H ...     step sizes the stability analysis warns against, and why
#include <iostream>
#include <string>

#include "advise_command.hpp"
#include "erkn/error.hpp"
#include "help.hpp"
#include "run_command.hpp"
#include "stability_command.hpp"
#include "tableau_command.hpp"

namespace {

int usage(bool help) {
  return erkn::cli::print_usage(
      "usage: erkn list [--json] | --version | --help\n"
      "       erkn tableau NAME (--v X | --series K | --poles VMAX)\n"
      "       erkn run [--quick | --full] [experiment options; erkn run --help]\n"
      "       erkn stability NAME|all [--vmax V --zmin Z --zmax Z --grid N --out DIR]\n"
      "       erkn advise NAME --h H (--spectrum L1,... | --problem P1|P2|P3|FPU)"
      " [--hessian LO,HI]\n"
      "Every command takes --methods-file F.json (repeatable): a user's methods, written by\n"
      "erkn-generate --json, join erkn's own. erkn COMMAND --help prints the command's usage.\n",
      help);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  if (argc == 2 && (command == "--help" || command == "-h" || command == "help"))
    return usage(true);
  if (command == "--version") {
    std::cout << "erkn " << ERKN_VERSION << "\n";
    return 0;
  }
  try {
    if (command != "run") argc = erkn::cli::load_methods_files(argc, argv);
    if (command == "list") return erkn::cli::list_command(argc - 1, argv + 1);
    if (command == "tableau") return erkn::cli::tableau_command(argc - 1, argv + 1);
    if (command == "run") return erkn::cli::run_command(argc - 1, argv + 1);
    if (command == "stability") return erkn::cli::stability_command(argc - 1, argv + 1);
    if (command == "advise") return erkn::cli::advise_command(argc - 1, argv + 1);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return usage(false);
}
