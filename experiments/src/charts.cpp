#include "charts.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <erkn/process.hpp>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "summary.hpp"

namespace ex {
namespace fs = std::filesystem;

std::string slug(const std::string& name) {
  std::string s;
  for (unsigned char ch : name) {
    if (std::isalnum(ch))
      s += char(std::tolower(ch));
    else if (!s.empty() && s.back() != '_')
      s += '_';
  }
  while (!s.empty() && s.back() == '_') s.pop_back();
  return s;
}

namespace {

const char* const kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                               "#e377c2", "#17becf", "#7f7f7f", "#bcbd22", "#393b79", "#637939",
                               "#8c6d31", "#843c39", "#7b4173", "#000000"};

// An ERKN method and its RKN limit (SolverTraits::limit_of) share a colour; the family sets dash
// type and point shape.
class Styles {
 public:
  std::string operator()(const SolverTraits& m) {
    const std::string& key = m.limit_of.empty() ? m.name : m.limit_of;
    auto [it, added] = colors_.try_emplace(key, int(colors_.size()));
    const char* color = kColors[it->second % std::size(kColors)];
    std::ostringstream s;
    s << "lc rgb '" << color << "' ";
    switch (m.family) {
      case Family::erkn:
        s << "dt 1 lw 2.2 pt 7 ps 0.9";
        break;
      case Family::rkn:
        s << "dt (8,5) lw 1.6 pt 6 ps 0.9";
        break;
      case Family::peer:
        s << "dt (2,4) lw 2.2 pt " << 4 + 2 * peers_++ << " ps 1.0";
        break;
    }
    return s.str();
  }

 private:
  std::map<std::string, int> colors_;
  int peers_ = 0;
};

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char ch : s) out += ch == '\'' ? std::string("''") : std::string(1, ch);
  return out + "'";
}

// One curve of a plot command: columns `columns` of `file` with lines and points, titled `title`.
std::string curve(const std::string& file, const std::string& columns, const std::string& style,
                  const std::string& title) {
  return quoted(file) + " u " + columns + " w lp " + style + " t " + quoted(title);
}

void write_header(std::ostream& gp, const std::string& title, const std::string& xlabel,
                  const std::string& ylabel) {
  gp << "set title " << quoted(title) << " noenhanced\n"
     << "set xlabel " << quoted(xlabel) << "\nset ylabel " << quoted(ylabel) << "\n"
     << "set logscale xy\nset format xy '10^{%L}'\nset grid lc rgb '#dddddd'\n"
     << "set key outside right top noenhanced spacing 1.15\n";
}

// Emits the plot for both terminals.
void write_outputs(std::ostream& gp, const std::string& stem, const std::string& plot) {
  gp << "set terminal pngcairo size 1000,620 enhanced font 'DejaVu Sans,11'\n"
     << "set output " << quoted(stem + ".png") << "\n"
     << plot << "\n"
     << "set terminal svg size 1000,620 dynamic enhanced font 'DejaVu Sans,11'\n"
     << "set output " << quoted(stem + ".svg") << "\n"
     << plot << "\nunset output\n";
}

std::ofstream open(const fs::path& p) {
  std::ofstream f(p);
  if (!f) throw std::runtime_error("cannot write " + p.string());
  f.precision(10);
  return f;
}

}  // namespace

void run_gnuplot(const fs::path& charts_dir, const std::string& script) {
  erkn::process::Request gnuplot;
  gnuplot.argv = {"gnuplot", script};
  gnuplot.working_directory = charts_dir.string();
  erkn::process::run_checked(gnuplot);
}

std::vector<ChartGroup> chart_groups(const std::vector<MethodResult>& methods) {
  const ChartGroup all[] = {{Group::paper, "", "the paper's methods"},
                            {Group::shipped_explicit, "_explicit", "erkn's explicit methods"},
                            {Group::shipped_other, "_other", "erkn's other implicit methods"}};
  std::vector<ChartGroup> out;
  for (const ChartGroup& g : all)
    if (g.group == Group::paper ||
        std::any_of(methods.begin(), methods.end(),
                    [&g](const MethodResult& m) { return in_group(m, g.group); }))
      out.push_back(g);
  return out;
}

namespace {

// The methods of a chart group: its registry methods and every peer.
bool on_chart(const SolverTraits& m, const ChartGroup& g) {
  return m.family == Family::peer || in_group(m, g.group);
}

std::string chart_title(const std::string& scene, const ChartGroup& g, const std::string& what) {
  return scene + ": " + g.title + " + peers — " + what;
}

void write_problem_data(const ProblemResult& r, const fs::path& charts_dir) {
  const std::string key = slug(r.key);
  for (const MethodResult& m : r.methods) {
    const std::string stem = "data/" + key + "_" + slug(m.name);
    std::ofstream sweep = open(charts_dir / (stem + ".dat"));
    sweep << "# steps h error grad_evals cpu_seconds\n";
    for (const Measurement& x : m.sweep)
      if (x.ok() && x.error > 0)
        sweep << x.steps << ' ' << x.h << ' ' << x.error << ' ' << x.stats.grad_evals << ' '
              << x.cpu << '\n';
    std::ofstream energy = open(charts_dir / (stem + "_energy.dat"));
    energy << "# t_end max|H_n-H_0| (h = " << m.energy.h << ")\n";
    for (size_t i = 0; i < m.energy.max_error.size() && m.energy.failure.empty(); ++i)
      energy << m.energy.t_end[i] << ' ' << m.energy.max_error[i] << '\n';
  }
}

}  // namespace

void chart_problem(const ProblemResult& r, const fs::path& charts_dir) {
  fs::create_directories(charts_dir / "data");
  write_problem_data(r, charts_dir);
  const std::string key = slug(r.key);
  std::ostringstream scene, err, energy;
  scene << r.key << ": " << r.title;
  err << "max-norm error of q at t = " << r.t_error;
  energy << "energy error, h = 1/" << std::lround(1 / r.methods.front().energy.h);
  for (const ChartGroup& g : chart_groups(r.methods)) {
    Styles style;
    std::string cost_plot = "plot ", cpu_plot = "plot ", energy_plot = "plot ";
    for (const MethodResult& m : r.methods) {
      if (!on_chart(m, g)) continue;
      const std::string stem = "data/" + key + "_" + slug(m.name);
      const std::string s = style(m);
      const std::string sep = cost_plot == "plot " ? "" : ", \\\n  ";
      cost_plot += sep + curve(stem + ".dat", "4:3", s, m.name);
      cpu_plot += sep + curve(stem + ".dat", "5:3", s, m.name);
      energy_plot += sep + curve(stem + "_energy.dat", "1:2", s, m.name);
    }
    const std::string stem = key + g.suffix;
    std::ofstream gp = open(charts_dir / "data" / (stem + ".gp"));
    write_header(gp, chart_title(scene.str(), g, "error vs cost"), "∇U evaluations (count)",
                 err.str());
    write_outputs(gp, stem + "_evals", cost_plot);
    write_header(gp, chart_title(scene.str(), g, "error vs CPU time"), "CPU time (s)", err.str());
    write_outputs(gp, stem + "_cpu", cpu_plot);
    write_header(gp, chart_title(scene.str(), g, energy.str()), "t_{end} (time units)",
                 "max_n |H_n − H_0|");
    write_outputs(gp, stem + "_energy", energy_plot);
    gp.close();
    run_gnuplot(charts_dir, "data/" + stem + ".gp");
  }
}

void chart_scaling(const ScalingResult& r, const fs::path& charts_dir) {
  fs::create_directories(charts_dir / "data");
  Styles style;
  std::string plot = "plot ";
  // Every peer, and of each group of registry methods the one cheapest at the largest size.
  std::vector<size_t> best;
  for (Group g : {Group::paper, Group::shipped_explicit, Group::shipped_other})
    if (const auto l = best_line(r, g)) best.push_back(*l);
  for (size_t l = 0; l < r.lines.size(); ++l) {
    if (r.lines[l].family != Family::peer && std::find(best.begin(), best.end(), l) == best.end())
      continue;
    const std::string stem = "data/scaling_" + slug(r.lines[l].name);
    std::ofstream dat = open(charts_dir / (stem + ".dat"));
    dat << "# N cpu_seconds_to_" << r.tolerances.front()
        << "\n# runs: N steps error grad_evals cpu\n";
    for (size_t i = 0; i < r.sizes.size(); ++i)
      for (const Measurement& m : r.lines[l].brackets[i])
        dat << "# " << r.sizes[i] << ' ' << m.steps << ' ' << m.error << ' ' << m.stats.grad_evals
            << ' ' << m.cpu << '\n';
    for (size_t i = 0; i < r.sizes.size(); ++i)
      if (const auto c = scaling_cpu(r, l, i)) dat << r.sizes[i] << ' ' << *c << '\n';
    plot += (plot == "plot " ? "" : ", \\\n  ") +
            curve(stem + ".dat", "1:2", style(r.lines[l]), r.lines[l].name);
  }
  std::ofstream gp = open(charts_dir / "data" / "scaling.gp");
  std::ostringstream title;
  title << "P1 sine-Gordon on [0, " << r.t_end << "]: CPU time to reach error "
        << r.tolerances.front();
  write_header(gp, title.str(), "N (grid points)", "CPU time (s)");
  gp << "set logscale x 2\nset format x '%g'\n";
  write_outputs(gp, "scaling", plot);
  gp.close();
  run_gnuplot(charts_dir, "data/scaling.gp");
}

void chart_stiff(const ProblemResult& r, double kappa, const fs::path& charts_dir) {
  fs::create_directories(charts_dir / "data");
  const std::string key = slug(r.key);
  for (const MethodResult& m : r.methods) {
    const std::string stem = "data/" + key + "_" + slug(m.name);
    std::ofstream ok = open(charts_dir / (stem + ".dat"));
    std::ofstream failed = open(charts_dir / (stem + "_failed.dat"));
    std::ofstream predicted = open(charts_dir / (stem + "_predicted.dat"));
    ok << "# steps h error grad_evals cpu_seconds\n";
    failed << "# steps h failure\n";
    // The V = 0 line's bound z* on h^2 kappa (cos u = 1, the stiffest point of grad^2 U).
    predicted << "# h = sqrt(z*/kappa), z* = first z with |tr S(0, z)| > 2\n";
    if (m.first_unstable_z) predicted << std::sqrt(*m.first_unstable_z / kappa) << '\n';
    for (const Measurement& x : m.sweep) {
      if (x.ok() && x.error > 0)
        ok << x.steps << ' ' << x.h << ' ' << x.error << ' ' << x.stats.grad_evals << ' ' << x.cpu
           << '\n';
      else if (!x.ok())
        failed << x.steps << ' ' << x.h << " # " << x.failure << '\n';
    }
  }
  std::ostringstream err;
  err << "max-norm error of q at t = " << r.t_error;
  for (const ChartGroup& g : chart_groups(r.methods)) {
    Styles style;
    std::string cpu_plot = "plot ", h_plot = "plot ";
    for (const MethodResult& m : r.methods) {
      if (!on_chart(m, g)) continue;
      const std::string stem = "data/" + key + "_" + slug(m.name);
      const std::string s = style(m);
      const std::string sep = cpu_plot == "plot " ? "" : ", \\\n  ";
      cpu_plot += sep + curve(stem + ".dat", "5:3", s, m.name);
      const std::string color = s.substr(0, s.find('\'', s.find('\'') + 1) + 1);  // "lc rgb '#..'"
      h_plot += sep + curve(stem + ".dat", "2:3", s, m.name) + ", " + quoted(stem + "_failed.dat") +
                " u 2:(1e3) w p " + color + " pt 2 ps 2 lw 2 notitle, " +
                quoted(stem + "_predicted.dat") + " u 1:(1e4) w p " + color +
                " pt 11 ps 1.6 notitle";
    }
    const std::string stem = key + g.suffix;
    std::ofstream gp = open(charts_dir / "data" / (stem + ".gp"));
    char scene[64];
    std::snprintf(scene, sizeof scene, "stiff sine-Gordon, κ = %g", kappa);
    write_header(gp, chart_title(scene, g, "error vs CPU time"), "CPU time (s)", err.str());
    write_outputs(gp, stem + "_cpu", cpu_plot);
    write_header(gp, chart_title(scene, g, "error vs h (×: failed; ▼: S(0, z) bound)"),
                 "step size h", err.str());
    // Completed runs (error below 100 (1 + |q|)), then a row of crosses and a row of triangles.
    gp << "set yrange [:3e4]\n";
    write_outputs(gp, stem + "_h", h_plot);
    gp.close();
    run_gnuplot(charts_dir, "data/" + stem + ".gp");
  }
}

}  // namespace ex
