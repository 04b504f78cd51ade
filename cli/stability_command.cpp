// erkn stability NAME|all [--vmax 100] [--zmin -50] [--zmax 50] [--grid 201] [--out DIR]
//
// For each method: DIR/stability_<id>.csv (the grid: V, z, tr S, det S, rho(S), class) and a
// chart DIR/stability_<id>.{png,svg} (region rho(S) <= 1 shaded, poles of the coefficients as
// vertical lines, the line V + z = 0 below which the test equation itself is unbounded). With
// "all": every method's CSV and chart plus the pages DIR/stability.{png,svg} (the paper's ERKN
// methods, like its figure 1), DIR/stability_explicit (the explicit splitting methods),
// DIR/stability_other (the other implicit ERKN methods) and DIR/stability_rkn (the RKN limits).
// Each chart's script is DIR/<chart>.{png,svg}.gp; one gnuplot process draws them all
// (DIR/stability_charts.gp). Charts need gnuplot on PATH; without it the CSVs and .gp scripts are
// still written and the command fails naming gnuplot.
#include "stability_command.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <erkn/process.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "erkn/error.hpp"
#include "erkn/method.hpp"
#include "erkn/stability.hpp"
#include "help.hpp"

namespace erkn::cli {
namespace {

struct Args {
  std::string name;
  double vmax = 100, zmin = -50, zmax = 50;
  int grid = 201;
  std::filesystem::path out = ".";
};

int usage(bool help = false) {
  return print_usage(
      "usage: erkn stability NAME|all [--vmax 100] [--zmin -50] [--zmax 50] [--grid 201]"
      " [--out DIR]\n",
      help);
}

double number(const std::string& option, const char* text) {
  char* end = nullptr;
  const double x = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(x) || std::isspace((unsigned char)text[0]))
    throw Error(option + " expects a finite number, got '" + text + "'");
  return x;
}

// Chart colour code of a class: 0 unstable, 1 periodic, 2 marginal, 3 singular/pole/other.
int code(StabilityClass c) {
  switch (c) {
    case StabilityClass::unstable:
      return 0;
    case StabilityClass::periodic:
      return 1;
    case StabilityClass::marginal:
      return 2;
    default:
      return 3;
  }
}

std::string fmt(double x, int digits = 3) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

struct Written {
  std::string csv, title;
  std::vector<double> poles;
};

Written write_csv(const Method& m, const Args& a) {
  const StabilityGrid g = stability_grid(m, a.vmax, a.zmin, a.zmax, a.grid, a.grid);
  Written w;
  w.csv = "stability_" + std::string(m.id_name()) + ".csv";
  long counts[6] = {};
  for (const StabilityPoint& p : g.points) ++counts[int(p.cls)];
  std::ofstream f(a.out / w.csv);
  if (!f) throw Error("cannot write " + (a.out / w.csv).string());
  f << "# erkn stability " << m.name() << ": S(V, z) of paper §4.1 on y'' + w^2 y = -eps y,"
    << " V = h^2 w^2, z = h^2 eps\n"
    << "# class: periodic |tr S| < 2 - tau, marginal ||tr S| - 2| <= tau, unstable |tr S| > 2 + tau"
    << " (tau = " << kTraceTolerance << "); singular: N = I + z Abar singular; pole: V at a pole\n"
    << "# max |det S - 1| = " << fmt(g.max_det_deviation)
    << " (relative to |s11 s22| + |s12 s21|: " << fmt(g.max_det_relative_deviation)
    << "; on rho(S) <= 1: " << fmt(g.max_det_deviation_bounded) << ")\n# poles in (0, vmax]:";
  for (double p : m.poles())
    if (p <= a.vmax) f << " " << fmt(p, 10), w.poles.push_back(p);
  f << "\n# points: periodic " << counts[int(StabilityClass::periodic)] << ", marginal "
    << counts[int(StabilityClass::marginal)] << ", unstable "
    << counts[int(StabilityClass::unstable)] << ", singular "
    << counts[int(StabilityClass::singular)] << ", pole " << counts[int(StabilityClass::pole)]
    << "\nV,z,trace,det,rho,code,class\n";
  f.precision(10);
  for (int i = 0; i < g.nv; ++i) {
    for (int j = 0; j < g.nz; ++j) {
      const StabilityPoint& p = g.point(i, j);
      f << p.V << "," << p.z << "," << p.trace << "," << p.det << "," << p.rho << "," << code(p.cls)
        << "," << to_string(p.cls) << "\n";
    }
    f << "\n";  // one block per V for gnuplot
  }
  w.title = std::string(m.name()) +
            "  (max|det S-1| on rho<=1: " + fmt(g.max_det_deviation_bounded, 2) + ")";
  std::cout << m.name() << ": " << (a.out / w.csv).string() << "  periodic "
            << counts[int(StabilityClass::periodic)] << ", unstable "
            << counts[int(StabilityClass::unstable)] << " of " << g.points.size()
            << " points; max |det S - 1| relative " << fmt(g.max_det_relative_deviation)
            << ", on rho<=1 " << fmt(g.max_det_deviation_bounded) << "\n";
  return w;
}

std::string panel(const Written& w, const Args& a, bool key) {
  std::ostringstream s;
  s << "unset arrow\n";
  for (double p : w.poles)
    s << "set arrow from " << p << ", graph 0 to " << p
      << ", graph 1 nohead front lc rgb '#d62728' lw 1.5 dt 2\n";
  s << "set title \"" << w.title << "\" noenhanced\n"
    << "set xrange [0:" << a.vmax << "]\nset yrange [" << a.zmin << ":" << a.zmax << "]\n"
    << (key ? "set key outside bottom center horizontal\n" : "unset key\n") << "plot '" << w.csv
    << "' using 1:2:6 with image notitle, "
    << "-x with lines lc rgb 'black' dt 3 title 'V+z=0', "
    << "NaN with boxes fs solid lc rgb '#9ecae1' title 'periodic (|tr S|<2)', "
    << "NaN with lines lc rgb '#d62728' dt 2 lw 1.5 title 'pole'\n";
  return s.str();
}

const char* kHeader =
    "set datafile separator ','\n"
    "set palette defined (0 'white', 1 '#9ecae1', 2 '#08519c', 3 '#d62728')\n"
    "set cbrange [0:3]\nunset colorbox\n"
    "set xlabel 'V = h^2{/Symbol w}^2'\nset ylabel 'z = h^2{/Symbol e}'\n";

// The charts: each one's script per format written as it is added (DIR/<stem>.<ext>.gp, to redraw
// it alone), all drawn by one gnuplot process (draw). One process per chart and format was ~100
// for "all", ~11 s of CPU (gnuplot's start each time), against ~1.4 s for one; the files are the
// same bytes. (`reset` and `unset output` between scripts: no setting or open file carries over.)
class Charts {
 public:
  explicit Charts(const Args& a) : a_(a) {}
  void add(const std::string& stem, const std::string& body, int w, int h) {
    for (const char* ext : {"png", "svg"}) {
      const std::string size = " size " + std::to_string(w) + "," + std::to_string(h);
      const std::string term =
          (std::string(ext) == "png" ? "pngcairo" : "svg") + size + " font 'Sans,10'";
      const std::string gp = stem + "." + ext + ".gp";
      std::ofstream(a_.out / gp) << "set terminal " << term << "\nset output '" << stem << "."
                                 << ext << "'\n"
                                 << kHeader << body;
      script_ << "reset\nload '" << gp << "'\nunset output\n";
    }
    stems_.push_back(stem);
  }
  void draw() const {
    const std::filesystem::path gp = a_.out / "stability_charts.gp";
    std::ofstream(gp) << script_.str();
    // No shell: the scripts name only files in DIR, which is gnuplot's working directory.
    process::Request gnuplot;
    gnuplot.argv = {"gnuplot", gp.filename().string()};
    gnuplot.working_directory = a_.out.string();
    const process::Result r = process::run(gnuplot);
    if (!r.ok())
      throw Error("gnuplot failed on " + gp.string() + " (is gnuplot installed?)" +
                  (r.err.empty() ? "" : ": " + r.err));
    for (const std::string& stem : stems_)
      std::cout << "chart: " << (a_.out / (stem + ".png")).string() << " (+ .svg)\n";
  }

 private:
  const Args& a_;
  std::ostringstream script_;
  std::vector<std::string> stems_;
};

// One page of panels, three columns up to six panels and four beyond.
void page(const Args& a, const std::vector<Written>& ws, const std::string& stem,
          const std::string& title, Charts& charts) {
  if (ws.empty()) return;
  const int cols = ws.size() <= 6 ? 3 : 4, rows = int((ws.size() + cols - 1) / cols);
  std::ostringstream s;
  s << "set multiplot layout " << rows << "," << cols << " title \"" << title << "\" noenhanced\n";
  for (size_t i = 0; i < ws.size(); ++i) s << panel(ws[i], a, false);
  s << "unset multiplot\n";
  charts.add(stem, s.str(), 500 * cols, 450 * rows);
}

// The arguments into a, checked; false: not a valid command line (usage).
bool parse(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw Error(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--vmax")
      a.vmax = number(arg, value());
    else if (arg == "--zmin")
      a.zmin = number(arg, value());
    else if (arg == "--zmax")
      a.zmax = number(arg, value());
    else if (arg == "--grid") {
      const double n = number(arg, value());
      if (n < 2 || n > 4001 || n != std::floor(n)) throw Error("--grid expects an integer 2..4001");
      a.grid = int(n);
    } else if (arg == "--out")
      a.out = value();
    else if (arg.rfind("--", 0) == 0)
      throw Error("unknown option " + arg);
    else if (a.name.empty())
      a.name = arg;
    else
      return false;
  }
  if (a.name.empty()) return false;
  if (!(a.vmax > 0) || !(a.zmax > a.zmin)) throw Error("need --vmax > 0 and --zmax > --zmin");
  if (a.vmax > generated::kPoleSearchMax)
    throw Error("--vmax " + fmt(a.vmax) + " is beyond the table of poles (V <= " +
                fmt(generated::kPoleSearchMax) + "): points there could not be classified");
  if (!std::isfinite(a.zmax - a.zmin)) throw Error("--zmax - --zmin is not a finite number");
  return true;
}

// Every method's CSV and chart, and the pages: the paper's ERKN methods (as in its figure 1), the
// explicit (splitting) methods, the other implicit ERKN methods, and the RKN limits.
void all_methods(const Args& a, Charts& charts) {
  std::vector<Written> paper_panels, explicit_panels, other_panels, rkn_panels;
  for (const Method& m : Method::all()) {
    const Written w = write_csv(m, a);
    charts.add(w.csv.substr(0, w.csv.size() - 4), panel(w, a, true), 800, 600);
    (m.kind() == Kind::rkn ? rkn_panels
     : m.is_explicit()     ? explicit_panels
     : m.from_paper()      ? paper_panels
                           : other_panels)
        .push_back(w);
  }
  const std::string legend =
      "   [blue: periodic |tr S| < 2 (rho = 1); white: unstable rho > 1; red dashed: poles; "
      "dotted: V + z = 0; tau = " +
      fmt(kTraceTolerance) + "]";
  const std::string test = ": stability of y''+w^2y=-ey, V=h^2w^2, z=h^2e";
  page(a, paper_panels, "stability", "The paper's ERKN methods" + test + legend, charts);
  page(a, explicit_panels, "stability_explicit",
       "Explicit ERKN (splitting) methods" + test + legend, charts);
  page(a, other_panels, "stability_other", "Other implicit ERKN methods" + test + legend, charts);
  page(a, rkn_panels, "stability_rkn",
       "RKN limits (force -(w^2+e)y, S depends on V+z only)" + legend, charts);
}

}  // namespace

int stability_command(int argc, char** argv) {
  if (asks_for_help(argc, argv)) return usage(true);
  Args a;
  if (!parse(argc, argv, a)) return usage();
  std::filesystem::create_directories(a.out);
  Charts charts(a);
  if (a.name == "all") {
    all_methods(a, charts);
  } else {
    const Written w = write_csv(Method::by_name(a.name), a);
    charts.add(w.csv.substr(0, w.csv.size() - 4), panel(w, a, true), 800, 600);
  }
  charts.draw();
  return 0;
}

}  // namespace erkn::cli
