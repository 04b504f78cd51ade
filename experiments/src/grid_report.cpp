// docs/grids.md and the grid charts, from the scenes as far as they got.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "charts.hpp"
#include "grid_scene_data.hpp"

namespace ex {
namespace fs = std::filesystem;
namespace {

std::string number(double x, int digits = 3) {
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

std::string stem(const GridScene& sc) { return "grid_" + slug(sc.key); }

bool is_peer(const Solver& s) { return s.family() == Family::peer; }

// One table cell: CPU time to tolerance; "—" not reached within the step cap (with the order's
// prediction of the steps it would need); "✗" failed; "·" not run.
std::string cell_text(const GridCell& c) {
  if (!c.failure.empty()) return "✗";
  if (!c.ran) return "·";
  if (c.cpu) return number(*c.cpu);
  if (c.predicted_steps > 0)
    return "— (≈" + std::to_string(std::lround(c.predicted_steps)) + " steps)";
  return "—";
}

void cpu_table(std::ostream& md, const GridScene& sc, const GridSceneConfig& cfg) {
  md << "CPU time (s, best of up to " << cfg.sweep.timing.repeats
     << " repeats, setup included) to reach max-norm error " << cfg.tolerance
     << " in q at t = 1, interpolated (log-log) between the two runs that bracket it. Step counts "
        "come from the method's order: the first run starts near the count that reached the "
        "tolerance at the previous N (4 steps, or omega_max T for Verlet, at the smallest N), the "
        "next is n (e / tol)^(1/p) 15 % beyond the tolerance. — not reached within "
     << cfg.sweep.max_steps
     << " steps (≈ the count the order predicts), ✗ failed (below), · not run: every ERKN method "
        "and peer runs at the smallest N; beyond it the cheapest ERKN method, the cheapest paper "
        "method and the peers that reached the tolerance at the previous N, while their cost "
        "there scaled by d log d (the predicted cost of one run) stays under "
     << number(cfg.line_budget) << " s.\n\n| method |";
  for (size_t i = 0; i < sc.dims.size(); ++i) md << " N = " << sc.sizes[i] << " |";
  md << "\n|---|";
  for (size_t i = 0; i < sc.dims.size(); ++i) md << "---:|";
  md << "\n";
  for (const GridLine& l : sc.lines) {
    md << "| " << l.solver->name() << (is_peer(*l.solver) ? " (peer)" : "")
       << (l.solver->from_paper() ? " (paper)" : "") << " |";
    for (const GridCell& c : l.cells) md << " " << cell_text(c) << " |";
    md << "\n";
  }
  for (const GridLine& l : sc.lines)
    for (size_t i = 0; i < l.cells.size(); ++i)
      if (l.cells[i].skipped.find("budget") != std::string::npos)  // (the others: see the legend)
        md << "\n· " << l.solver->name() << ", N = " << sc.sizes[i] << ": " << l.cells[i].skipped
           << "\n";
  for (const GridLine& l : sc.lines)
    for (size_t i = 0; i < l.cells.size(); ++i)
      if (!l.cells[i].failure.empty())
        md << "\n✗ " << l.solver->name() << ", N = " << sc.sizes[i] << ": " << l.cells[i].failure
           << "\n";
  md << "\nReferences: ";
  for (size_t i = 0; i < sc.references.size(); ++i)
    md << (i ? "; " : "") << "N = " << sc.sizes[i] << ": " << sc.references[i].method
       << " (agreement with half the steps " << number(sc.references[i].accuracy, 2) << ")";
  md << ".\n\n![CPU time to tolerance (the methods run at more than one N)](charts/" << stem(sc)
     << "_cpu.png)\n\n";
}

void step_table(std::ostream& md, const GridScene& sc) {
  if (sc.step_times.empty()) return;
  md << "Time per step against d (CPU s per step, (best of 3 runs of 2k steps - best of 3 of k) / "
        "k with k doubled from 4 until a run takes 20 ms, at the step size that reached the "
        "tolerance at the largest N), for the cheapest ERKN method, paper method and peer there; "
        "fit t = c d log2 d (c from the mean of log(t / d log2 d)).\n\n| N | d |";
  for (const StepTimes& st : sc.step_times) md << " " << st.solver->name() << " (s) |";
  md << "\n|---:|---:|";
  for (size_t i = 0; i < sc.step_times.size(); ++i) md << "---:|";
  md << "\n";
  for (size_t i = 0; i < sc.step_dims.size(); ++i) {
    md << "| " << sc.step_sizes[i] << " | " << sc.step_dims[i] << " |";
    for (const StepTimes& st : sc.step_times)
      md << " "
         << (i < st.seconds.size() && st.seconds[i] ? number(*st.seconds[i]) : std::string("✗"))
         << " |";
    md << "\n";
  }
  md << "\n";
  for (const StepTimes& st : sc.step_times) {
    md << "- " << st.solver->name() << " (h = " << number(st.h) << "): ";
    if (st.c > 0)
      md << "c = " << number(st.c) << " s, largest deviation of a point from c d log2 d "
         << number(100 * st.deviation, 2) << " %, least-squares slope of log t against log d "
         << number(st.slope);
    if (!st.failure.empty()) md << (st.c > 0 ? "; " : "") << "failed: " << st.failure;
    if (st.bytes_per_unknown)
      md << "; erkn::Integrator memory at N = " << sc.sizes[sc.dims.size() - 1] << ": "
         << number(*st.bytes_per_unknown) << " bytes per unknown ("
         << number(*st.bytes_per_unknown / 8)
         << " doubles; malloc's bytes in use while it "
            "lives, after one step)";
    md << "\n";
  }
  md << "\n![time per step](charts/" << stem(sc) << "_step.png)\n";
}

void dense_table(std::ostream& md, const std::vector<std::pair<int, double>>& dense) {
  if (dense.empty()) return;
  md << "\n## General sparse M: the dense path\n\nerkn does not apply functions of V to a general "
        "sparse M matrix-free (docs/scale.md, \"General sparse M\"); such an M goes through "
        "`Stiffness::dense`, whose setup is one symmetric eigendecomposition (O(d^3) time, 2 d^2 "
        "doubles) and whose transforms are d x d products (O(d^2) per transform). Setup CPU time "
        "measured in this run:\n\n| d | eigendecomposition (s) | matrices (MB) "
        "|\n|---:|---:|---:|\n";
  for (const auto& [d, seconds] : dense)
    md << "| " << d << " | " << number(seconds) << " | "
       << number(2.0 * 8 * double(d) * double(d) / 1e6) << " |\n";
}

// The data file of one CPU-time line; its number of points.
int write_cpu_data(const fs::path& dat, const GridScene& sc, const GridLine& l, double tol) {
  std::ofstream f(dat);
  f << "# N cpu_seconds_to_" << tol << "\n";
  int points = 0;
  for (size_t i = 0; i < l.cells.size(); ++i)
    if (l.cells[i].cpu) f << sc.sizes[i] << ' ' << *l.cells[i].cpu << '\n', ++points;
  return points;
}

std::string step_plot(const GridScene& sc, const fs::path& charts) {
  std::string plot;
  for (const StepTimes& st : sc.step_times) {
    const std::string dat = "data/" + stem(sc) + "_step_" + slug(st.solver->name()) + ".dat";
    std::ofstream f(charts / dat);
    f << "# d seconds_per_step fit_c_d_log2_d\n";
    for (size_t i = 0; i < st.seconds.size(); ++i) {
      if (!st.seconds[i]) continue;
      const double d = double(sc.step_dims[i]);
      f << sc.step_dims[i] << ' ' << *st.seconds[i] << ' ' << st.c * d * std::log2(d) << '\n';
    }
    if (st.c <= 0) continue;
    plot += std::string(plot.empty() ? "plot " : ", \\\n  ") + quoted(dat) +
            " u 1:2 w p pt 7 ps 1.3 t " + quoted(st.solver->name()) + ", " + quoted(dat) +
            " u 1:3 w l lw 1.5 t " + quoted(st.solver->name() + ": fit c d log2 d");
  }
  return plot;
}

}  // namespace

void chart_grid_scene(const GridScene& sc, const fs::path& charts, double tolerance) {
  const fs::path data = charts / "data";
  fs::create_directories(data);
  std::string plot;
  for (const GridLine& l : sc.lines) {
    const std::string dat = "data/" + stem(sc) + "_" + slug(l.solver->name()) + ".dat";
    // Lines measured at one N only are in the table, not in the chart (a single point each).
    if (write_cpu_data(charts / dat, sc, l, tolerance) < std::min<int>(2, sc.dims.size())) continue;
    plot += std::string(plot.empty() ? "plot " : ", \\\n  ") + quoted(dat) + " u 1:2 w lp lw 2 " +
            (is_peer(*l.solver) ? "dt (2,4) pt 4" : "dt 1 pt 7") + " t " + quoted(l.solver->name());
  }
  const std::string steps = step_plot(sc, charts);
  const fs::path gp = data / (stem(sc) + ".gp");
  std::ofstream g(gp);
  const auto outputs = [&](const std::string& name, const std::string& body) {
    if (body.empty()) return;
    for (const char* ext : {"png", "svg"})
      g << (std::string(ext) == "png"
                ? "set terminal pngcairo size 1000,620 font 'DejaVu Sans,11'\n"
                : "set terminal svg size 1000,620 dynamic font 'DejaVu Sans,11'\n")
        << "set output " << quoted(name + "." + ext) << "\n"
        << body << "\n";
    g << "unset output\n";
  };
  g << "set logscale xy\nset grid lc rgb '#dddddd'\nset key outside right top noenhanced\n"
    << "set title " << quoted(sc.title + ": CPU time to error " + number(tolerance))
    << " noenhanced\nset xlabel 'N (points per axis)'\nset ylabel 'CPU time (s)'\n"
    << "set logscale x 2\n";
  outputs(stem(sc) + "_cpu", plot);
  g << "set title " << quoted(sc.title + ": time per step against d") << " noenhanced\n"
    << "set xlabel 'd (unknowns)'\nset ylabel 'seconds per step'\nset logscale x 10\n";
  outputs(stem(sc) + "_step", steps);
  g.close();
  run_gnuplot(charts, "data/" + stem(sc) + ".gp");  // (paths in it are relative to charts)
}

void write_grid_report(const fs::path& out, const std::vector<GridScene>& scenes,
                       const GridSceneConfig& cfg, const std::string& command,
                       const std::string& status,
                       const std::vector<std::pair<int, double>>& dense) {
  std::ofstream md(out / "grids.md");
  md << "# Large grid scenes\n\nWritten by `" << command << "`: " << status
     << ". Do not edit: every number below comes from that run. M is the shifted discrete "
        "Laplacian of a tensor grid (erkn::Stiffness::grid; FFTW r2c/c2r when every axis is "
        "periodic, else r2r transforms); the peers use "
        "their own FFTW transforms. The RKN limits are left out (they must resolve omega_max ~ "
        "2 sqrt(k)/dx).\n";
  for (const GridScene& sc : scenes) {
    if (sc.dims.empty() && sc.failure.empty()) continue;
    md << "\n## " << sc.title << "\n\n";
    if (sc.wall > 0) md << "Scene wall time " << number(sc.wall) << " s.\n\n";
    if (!sc.failure.empty()) md << "**Stopped early:** " << sc.failure << "\n\n";
    cpu_table(md, sc, cfg);
    step_table(md, sc);
  }
  dense_table(md, dense);
  if (!md) throw std::runtime_error("cannot write " + (out / "grids.md").string());
}

}  // namespace ex
