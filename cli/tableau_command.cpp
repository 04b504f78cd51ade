#include "tableau_command.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <span>
#include <string>
#include <vector>

#include "erkn/error.hpp"
#include "erkn/method.hpp"
#include "help.hpp"
#include "json.hpp"

namespace erkn::cli {
namespace {

// A processed method's kernel order and pi^-1, the pre-processor the runtime applies to a state
// before the kernel steps (erkn/table.hpp: drift pre_drift[k] h, kick pre_kick[k] and
// pre_modified[k], ..., drift pre_drift[npre] h; pi is its exact inverse).
void print_processor(const Method& m) {
  const generated::Table& t = m.table();
  const auto list = [](const double* x, int n) { return json_list(std::vector<double>(x, x + n)); };
  std::cout << ",\n \"kernel_order\": " << m.kernel_order()
            << ",\n \"pre_drift\": " << list(t.pre_drift, t.npre + 1)
            << ",\n \"pre_kick\": " << list(t.pre_kick, t.npre)
            << ",\n \"pre_modified\": " << list(t.pre_modified, t.npre);
}

// {"method", "stages", "order", "c", "d", "b", "bbar", "abar"} with each coefficient rendered
// by `value(index)` (index in table order b_1..b_s, bbar_1..bbar_s, abar_11, abar_21, ...).
void print_tableau(const Method& m, const std::function<std::string(int)>& value) {
  const int s = m.stages();
  std::vector<double> c(m.table().c, m.table().c + s), d(m.table().d, m.table().d + s);
  std::cout << "{\"method\": " << json_string(std::string(m.name())) << ", \"stages\": " << s
            << ", \"order\": " << m.order() << ",\n \"c\": " << json_list(c)
            << ",\n \"d\": " << json_list(d);
  if (m.has_modified_kicks())
    std::cout << ",\n \"modified\": "
              << json_list(std::vector<double>(m.modified().begin(), m.modified().end()));
  if (m.is_processed()) print_processor(m);
  std::cout << ",\n \"b\": [";
  for (int i = 0; i < s; ++i) std::cout << (i ? ", " : "") << value(i);
  std::cout << "],\n \"bbar\": [";
  for (int i = 0; i < s; ++i) std::cout << (i ? ", " : "") << value(s + i);
  std::cout << "],\n \"abar\": [";
  for (int i = 0; i < s; ++i) {
    std::cout << (i ? ", " : "") << "[";
    for (int j = 0; j <= i; ++j)
      std::cout << (j ? ", " : "") << value(2 * s + Coefficients::packed(i, j));
    std::cout << "]";
  }
  std::cout << "]}\n";
}

int usage(bool help = false) {
  return print_usage(
      "usage: erkn tableau NAME --v X        coefficients at v = h^2*lambda = X >= 0\n"
      "       erkn tableau NAME --series K   Taylor coefficients of v^0..v^K\n"
      "       erkn tableau NAME --poles VMAX real poles in (0, VMAX]\n",
      help);
}

}  // namespace

double parse_number(const char* option, const char* text) {
  char* end = nullptr;
  double x = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(x) || std::isspace((unsigned char)text[0]))
    throw Error(std::string(option) + " expects a finite number, got '" + text + "'");
  return x;
}

// A list of error constants, null where the generator found no failing condition.
std::string json_constants(std::span<const double> xs) {
  std::string out = "[";
  for (size_t i = 0; i < xs.size(); ++i) out += (i ? ", " : "") + json_number_or_null(xs[i]);
  return out + "]";
}

// One JSON object per method: name, kind, stages, certified order, generalized order, the
// error constants, poles, modified-kick coefficients e_i (empty: plain kicks), whether it is
// processed (psi = pi o K o pi^-1; order is psi's) and its kernel's order, source, whether
// it is one of the paper's methods, and the id
// (erkn.methods() has the same).
void list_json() {
  std::cout << "[";
  bool first = true;
  for (const Method& m : Method::all()) {
    std::vector<double> generalized(m.generalized_order().begin(), m.generalized_order().end());
    std::vector<double> poles(m.poles().begin(), m.poles().end());
    std::vector<double> modified(m.modified().begin(), m.modified().end());
    std::cout << (first ? "\n" : ",\n") << " {\"name\": " << json_string(std::string(m.name()))
              << ", \"kind\": " << json_string(std::string(m.kind_name()))
              << ", \"stages\": " << m.stages() << ", \"order\": " << m.order()
              << ", \"generalized_order\": " << json_list(generalized)
              << ", \"error_constant\": " << json_number_or_null(m.error_constant())
              << ", \"generalized_error_constant\": "
              << json_constants(m.generalized_error_constant())
              << ", \"poles\": " << json_list(poles) << ", \"modified\": " << json_list(modified)
              << ", \"processed\": " << (m.is_processed() ? "true" : "false")
              << ", \"kernel_order\": " << m.kernel_order()
              << ", \"source\": " << json_string(std::string(m.reference()))
              << ", \"paper\": " << (m.from_paper() ? "true" : "false")
              << ", \"id\": " << json_string(std::string(m.id_name())) << "}";
    first = false;
  }
  std::cout << "\n]\n";
}

int load_methods_files(int argc, char** argv) {
  int kept = 0;
  for (int i = 0; i < argc; ++i) {
    if (std::string(argv[i]) == "--methods-file") {
      if (i + 1 >= argc)
        throw Error("--methods-file needs a file (erkn-generate --json writes it)");
      Method::load(argv[++i]);
    } else {
      argv[kept++] = argv[i];
    }
  }
  return kept;
}

int list_command(int argc, char** argv) {
  const auto list_usage = [](bool help) {
    return print_usage(
        "usage: erkn list [--json] [--methods-file F.json]...   every method: kind, stages,\n"
        "       certified order, source; with a user's methods (erkn-generate --json), checked\n"
        "       against the order conditions they claim\n",
        help);
  };
  if (asks_for_help(argc, argv)) return list_usage(true);
  if (argc == 2 && std::string(argv[1]) == "--json") {
    list_json();
    return 0;
  }
  if (argc != 1) return list_usage(false);
  int width = 4;
  for (const Method& m : Method::all()) width = std::max(width, int(m.name().size()));
  // Left-aligned text, right-aligned numbers under the ends of their headers.
  const auto row = [&](std::string_view name, std::string_view kind, const std::string& stages,
                       const std::string& order, std::string_view reference) {
    std::cout << std::left << std::setw(width) << name << "  " << std::setw(8) << kind << std::right
              << std::setw(6) << stages << std::setw(7) << order << "  " << reference << "\n";
  };
  row("name", "kind", "stages", "order", "reference");
  for (const Method& m : Method::all())
    row(m.name(), m.kind_name(), std::to_string(m.stages()), std::to_string(m.order()),
        m.reference());
  return 0;
}

int tableau_command(int argc, char** argv) {
  if (asks_for_help(argc, argv)) return usage(true);
  if (argc != 4) return usage();
  const Method& m = Method::by_name(argv[1]);
  const std::string option = argv[2];
  const double x = parse_number(argv[2], argv[3]);
  if (option == "--v") {
    Coefficients k = m.at(x);  // refuses negative v and v near a pole, naming it
    std::vector<double> all(k.b.begin(), k.b.begin() + k.s);
    all.insert(all.end(), k.bbar.begin(), k.bbar.begin() + k.s);
    // (packed(s, 0): the number of entries in s rows)
    all.insert(all.end(), k.abar_packed.begin(),
               k.abar_packed.begin() + Coefficients::packed(k.s, 0));
    print_tableau(m, [&](int i) { return json_number(all[i]); });
  } else if (option == "--series") {
    if (x < 0 || x != std::floor(x) || x >= generated::kSeriesTerms)
      throw Error("--series expects an integer K in [0, " +
                  std::to_string(generated::kSeriesTerms - 1) + "], got '" + argv[3] + "'");
    print_tableau(m, [&](int i) {
      std::vector<double> coef;
      for (int k = 0; k <= int(x); ++k) coef.push_back(m.series(i, k));
      return json_list(coef);
    });
  } else if (option == "--poles") {
    if (x <= 0 || x > generated::kPoleSearchMax)
      throw Error("--poles expects VMAX in (0, " + json_number(generated::kPoleSearchMax) +
                  "] (poles are tabulated up to there), got '" + argv[3] + "'");
    std::vector<double> poles;
    for (double p : m.poles())
      if (p <= x) poles.push_back(p);
    std::cout << json_list(poles) << "\n";
  } else {
    return usage();
  }
  return 0;
}

}  // namespace erkn::cli
