// The erkn CLI started as a user would (no shell between): exact refusals for the inputs issue
// 12 lists, no shell injection through --out, and a bounded fuzz of argument lists (fixed seed):
// no signal, no hang, never exit 0 on junk.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <erkn/advisor.hpp>
#include <erkn/method.hpp>
#include <erkn/process.hpp>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Args = std::vector<std::string>;

erkn::process::Result erkn_cli(const Args& args, const std::string& cwd = "") {
  erkn::process::Request r;
  r.argv = {ERKN_CLI};
  r.argv.insert(r.argv.end(), args.begin(), args.end());
  r.working_directory = cwd;
  r.timeout_seconds = 30;
  return erkn::process::run(r);
}

std::string joined(const Args& args) {
  std::string s = "erkn";
  for (const std::string& a : args) s += " [" + a + "]";
  return s;
}

fs::path fresh_directory(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("erkn_cli_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void expect_refusal(const Args& args, const std::string& message) {
  const erkn::process::Result r = erkn_cli(args);
  EXPECT_NE(r.exit_code, 0) << joined(args);
  EXPECT_EQ(r.signal, 0) << joined(args);
  EXPECT_FALSE(r.timed_out) << joined(args);
  EXPECT_NE(r.err.find(message), std::string::npos)
      << joined(args) << ": stderr '" << r.err << "' lacks '" << message << "'";
}

TEST(Cli, RefusesTheInputsOfIssue12) {
  expect_refusal({"list", "junk"}, "usage: erkn list");
  expect_refusal({"run", "--steps", "1/0"}, "--steps: step size 1/0 must be a finite number");
  expect_refusal({"run", "--steps", "abc"},
                 "--steps expects step sizes like 0.025 or 1/40, got 'abc'");
  expect_refusal({"run", "--methods", ""}, "--methods expects a comma-separated list");
  expect_refusal({"run", "--problems", ""}, "--problems expects a comma-separated list");
  expect_refusal({"run", "--methods", "SERKN2s4,,RKN2s4"}, "without empty items");
  const std::string name(erkn::Method::all()[0].name());
  expect_refusal({"stability", name, "--vmax", "1e6", "--grid", "5"}, "beyond the table of poles");
  expect_refusal({"stability", name, "--vmax", "1e308", "--grid", "5"},
                 "beyond the table of poles");
  expect_refusal({"stability", name, "--vmax", "inf"}, "--vmax expects a finite number");
  expect_refusal({"stability", name, "--zmin", "-1e308", "--zmax", "1e308", "--grid", "5"},
                 "not a finite number");
}

// erkn run starts the erkn-experiments beside erkn, found at run time: an erkn without one says
// so (the path and how to build it); the build tree's erkn, beside its erkn-experiments, starts it.
TEST(Cli, RunFindsErknExperimentsBesideItOrSaysItIsMissing) {
  const fs::path alone = fresh_directory("alone") / "erkn";
  fs::copy_file(ERKN_CLI, alone);
  erkn::process::Request r;
  r.argv = {alone.string(), "run", "--help"};
  r.timeout_seconds = 30;
  const erkn::process::Result missing = erkn::process::run(r);
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(
      missing.err.find("erkn run needs the experiments program " +
                       (alone.parent_path() / "erkn-experiments").string() + ", which is missing"),
      std::string::npos)
      << missing.err;
  EXPECT_NE(missing.err.find("-DERKN_BUILD_EXPERIMENTS=ON"), std::string::npos) << missing.err;
  const erkn::process::Result beside = erkn_cli({"run", "--help"});
  EXPECT_EQ(beside.exit_code, 0) << beside.err;
  EXPECT_NE(beside.out.find("usage: erkn-experiments"), std::string::npos) << beside.out;
  fs::remove_all(alone.parent_path());
}

// erkn tableau shows a processed method's pre-processor pi^-1 (npre + 1 drifts, npre kicks) and
// its kernel's order; an unprocessed method shows none (negative control).
TEST(Cli, TableauShowsTheProcessorOfProcessedMethods) {
  int processed = 0;
  for (const erkn::Method& m : erkn::Method::all()) {
    const erkn::process::Result r = erkn_cli({"tableau", std::string(m.name()), "--v", "0.5"});
    ASSERT_EQ(r.exit_code, 0) << m.name() << r.err;
    if (!m.is_processed()) {
      EXPECT_EQ(r.out.find("pre_drift"), std::string::npos) << m.name();
      continue;
    }
    ++processed;
    const erkn::generated::Table& t = m.table();
    const auto count = [&](const std::string& key) {  // entries of the list after "key": [
      const size_t at = r.out.find("\"" + key + "\": [");
      if (at == std::string::npos) return -1;
      const std::string list = r.out.substr(at, r.out.find(']', at) - at);
      return int(std::count(list.begin(), list.end(), ',')) + 1;
    };
    EXPECT_EQ(count("pre_drift"), t.npre + 1) << r.out;
    EXPECT_EQ(count("pre_kick"), t.npre) << r.out;
    EXPECT_EQ(count("pre_modified"), t.npre) << r.out;
    EXPECT_NE(r.out.find("\"kernel_order\": " + std::to_string(m.kernel_order())),
              std::string::npos)
        << r.out;
  }
  EXPECT_GT(processed, 0);
}

TEST(Cli, AdviseFlagsPolesAndResonancesAndAcceptsTheRest) {
  for (const erkn::Method& m : erkn::Method::all()) {
    const std::string name(m.name());
    for (double P : m.poles()) {
      const erkn::process::Result r =
          erkn_cli({"advise", name, "--h", std::to_string(std::sqrt(P)), "--spectrum", "1"});
      EXPECT_EQ(r.exit_code, 3) << name << r.out << r.err;
      EXPECT_NE(r.out.find("pole"), std::string::npos) << r.out;
    }
    // A small h far from every band and pole (negative control).
    const erkn::process::Result ok =
        erkn_cli({"advise", name, "--h", "0.01", "--spectrum", "1,4", "--hessian", "0,1"});
    EXPECT_EQ(ok.exit_code, 0) << name << ok.out << ok.err;
    EXPECT_NE(ok.out.find("no eigenvalue of M"), std::string::npos) << ok.out;
    if (m.kind() != erkn::Kind::erkn) continue;
    // h sqrt(lambda) = pi exactly: the library's advisor flags h (the resonance band, or for a
    // method whose stability polynomial leaves [-2, 2] there, such as SABAC1's corrector, an
    // instability); the CLI reports each of its findings, with a suggestion.
    const double h = 0.06283185307179587;
    const erkn::StepSizeAdvice advice =
        erkn::advise_step_size(m, Eigen::Vector2d(0, 2500), h, {0, 12});
    ASSERT_FALSE(advice.findings.empty()) << name;
    const erkn::process::Result r = erkn_cli({"advise", name, "--h", "0.06283185307179587",
                                              "--spectrum", "0,2500", "--hessian", "0,12"});
    EXPECT_EQ(r.exit_code, 3) << name << r.out << r.err;
    for (const erkn::AdvisorFinding& f : advice.findings)
      EXPECT_NE(r.out.find(std::string(erkn::to_string(f.hazard))), std::string::npos)
          << name << ": " << r.out;
    EXPECT_NE(r.out.find("nearest step size without findings"), std::string::npos) << r.out;
  }
  const erkn::process::Result p = erkn_cli({"advise", "SERKN2s4", "--h", "0.1", "--problem", "P2"});
  EXPECT_TRUE(p.exit_code == 0 || p.exit_code == 3) << p.err;
  EXPECT_NE(p.out.find("Hessian of U in"), std::string::npos) << p.out << p.err;
  // FPU at h omega = pi (omega = 50): its Hessian at the initial state puts h in a resonance
  // band. SERKN2s4's run keeps its energy error below 0.5 there (0.16 over 1e5 steps,
  // docs/stability-advisor.md), so the trial clears h and the resonance is information; Strang's
  // at 0.999 pi blows up, and is flagged.
  const erkn::process::Result f =
      erkn_cli({"advise", "SERKN2s4", "--h", "0.06283185307179587", "--problem", "FPU"});
  EXPECT_EQ(f.exit_code, 0) << f.out << f.err;
  EXPECT_NE(f.out.find("information"), std::string::npos) << f.out;
  EXPECT_NE(f.out.find("resonance"), std::string::npos) << f.out;
  const erkn::process::Result g =
      erkn_cli({"advise", "Strang", "--h", "0.06276902", "--problem", "FPU"});
  EXPECT_EQ(g.exit_code, 3) << g.out << g.err;
  EXPECT_NE(g.out.find("trial run"), std::string::npos) << g.out;
  expect_refusal({"advise", "SERKN2s4", "--h", "0.1", "--problem", "P9"}, "unknown problem");
  expect_refusal({"advise", "SERKN2s4", "--h", "0.1", "--spectrum", "1,,2"}, "finite numbers");
}

TEST(Cli, NoShellBetweenErknAndGnuplot) {
  const fs::path cwd = fresh_directory("injection");
  const std::string out = "d'; touch INJECTED; echo '";
  const std::string name(erkn::Method::all()[0].name());
  const erkn::process::Result r =
      erkn_cli({"stability", name, "--grid", "5", "--out", out}, cwd.string());
  EXPECT_FALSE(fs::exists(cwd / "INJECTED")) << r.out << r.err;
  EXPECT_FALSE(fs::exists(cwd / out / "INJECTED"));
  const std::string csv = "stability_" + std::string(erkn::Method::all()[0].id_name());
  EXPECT_TRUE(fs::exists(cwd / out / (csv + ".csv")));
  // The chart is drawn when gnuplot is there (it is wherever install-deps.sh ran).
  if (erkn::process::run({{"gnuplot", "--version"}}).ok()) {
    EXPECT_TRUE(r.ok()) << r.err;
    EXPECT_TRUE(fs::exists(cwd / out / (csv + ".png")));
  }
  fs::remove_all(cwd);
}

// Junk for an option: values every command refuses for it.
const std::vector<std::pair<std::string, Args>> kJunk = {
    {"--v", {"-1", "-0.5", "nan", "inf", "abc", "", "1e999", "1/0", "0x", " 1"}},
    {"--series", {"-1", "0.5", "1e9", "nan", "abc", "", "1e999"}},
    {"--poles", {"0", "-1", "1e9", "nan", "abc", "", "inf"}},
    {"--vmax", {"0", "-1", "1e6", "1e308", "nan", "inf", "abc", "", "1e999"}},
    {"--zmin", {"nan", "abc", "", "1e999", "-inf", "100"}},
    {"--zmax", {"nan", "abc", "", "1e999", "inf", "-100"}},
    {"--grid", {"1", "0", "-5", "2.5", "1e9", "nan", "abc", ""}},
    {"--steps", {"1/0", "abc", "", "0", "-1", "nan", "1/", "/3", "1e-300", "20", "0.1,", ",0.1"}},
    {"--methods", {"", ",", "SERKN2s4,,RKN2s4", "NOPE", "'; touch X"}},
    {"--problems", {"", "P9", ",P1", "P1,"}},
    {"--h", {"0", "-1", "nan", "inf", "abc", "", "1e999"}},
    {"--spectrum", {"", ",", "1,,2", "-1", "nan", "abc", "1e999"}},
    {"--problem", {"", "P9", "p1", "'; touch X"}},
    {"--hessian", {"", "1", "2,1", "0,nan", "0,1,2", "abc,1"}},
};

const Args& junk_for(const std::string& option) {
  for (const auto& [o, values] : kJunk)
    if (o == option) return values;
  static const Args none;
  return none;
}

struct Generator {
  std::mt19937 rng{20261123};  // fixed seed: the same argument lists on every run
  std::string out;
  template <class T>
  const T& pick(const std::vector<T>& v) {
    return v[std::uniform_int_distribution<size_t>(0, v.size() - 1)(rng)];
  }
  std::string method() {
    return std::string(erkn::Method::all()[index(erkn::Method::all().size())].name());
  }
  size_t index(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); }
  std::string number(double lo, double hi) {
    return std::to_string(std::uniform_real_distribution<double>(lo, hi)(rng));
  }

  // A valid command line (option, value pairs after the command words); never a real `run`.
  Args valid() {
    switch (index(5)) {
      case 4:
        return {"advise",     method(),        "--h",       number(0.001, 0.5),
                "--spectrum", number(0, 3000), "--hessian", "0," + number(0, 20)};
      case 0:
        return {"tableau", method(), "--v", number(0, 5)};
      case 1:
        return {"tableau", method(), "--series", std::to_string(index(3))};
      case 2:
        return {"tableau", method(), "--poles", number(1, 1000)};
      default:
        return {"stability", index(4) ? method() : "all",
                "--vmax",    number(1, 100),
                "--zmin",    number(-20, 0),
                "--zmax",    number(1, 20),
                "--grid",    std::to_string(2 + index(3)),
                "--out",     out};
    }
  }
  Args run_line() {
    return {"run", "--quick", "--steps", "1/40", "--methods", method(), "--problems", "P2"};
  }

  // One corruption of a command line that makes it junk.
  Args junk() {
    Args a = index(3) == 0 ? run_line() : valid();
    std::vector<size_t> options;
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i].rfind("--", 0) == 0 && !junk_for(a[i]).empty() && i + 1 < a.size())
        options.push_back(i);
    switch (index(6)) {
      case 0:
      case 1: {  // a junk value
        const size_t i = pick(options);
        a[i + 1] = pick(junk_for(a[i]));
        return a;
      }
      case 2:  // an option without its value
        a.push_back(pick(options) == options.front() ? a[options.front()] : a[options.back()]);
        return a;
      case 3:  // an unknown option
        a.insert(a.begin() + 1 + index(a.size()), "--bogus" + std::to_string(index(100)));
        return a;
      case 4:  // a junk method name or command
        if (a[0] == "run") return {"run", "--" + std::to_string(index(1000))};
        a[1] = pick(Args{"", "SERKN", "'; touch X", std::string(5000, 'x'), a[1] + "x", "--v"});
        return a;
      default:
        return Args{pick(Args{"", "lst", "tableaux", "--help", "RUN", "list", "x"}), "y"};
    }
  }
};

TEST(Cli, FuzzedArgumentListsNeverCrashHangOrAcceptJunk) {
  const fs::path dir = fresh_directory("fuzz");
  Generator gen;
  gen.out = (dir / "out").string();
  int junk = 0, valid = 0;
  for (int n = 0; n < 300; ++n) {
    const bool is_junk = n % 5 != 0;
    const Args args = is_junk ? gen.junk() : gen.valid();
    const erkn::process::Result r = erkn_cli(args, dir.string());
    EXPECT_EQ(r.signal, 0) << joined(args) << "\n" << r.err;
    EXPECT_FALSE(r.timed_out) << joined(args);
    if (is_junk) {
      ++junk;
      EXPECT_NE(r.exit_code, 0) << "junk accepted: " << joined(args) << "\n" << r.out;
      EXPECT_FALSE(r.err.empty()) << "refused without a word: " << joined(args);
    } else {
      ++valid;
      EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1 || (args[0] == "advise" && r.exit_code == 3))
          << joined(args) << "\n"
          << r.err;
    }
  }
  EXPECT_FALSE(fs::exists(dir / "X"));
  std::cout << "fuzzed " << junk << " junk and " << valid << " valid argument lists\n";
  fs::remove_all(dir);
}

}  // namespace
