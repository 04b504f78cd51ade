#include "raw_results.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace ex {
namespace {

std::string family_key(Family f) {
  return f == Family::erkn ? "erkn" : f == Family::rkn ? "rkn" : "peer";
}

// 17 significant digits (round-trips); non-finite values as CSV "inf"/"nan", JSON null.
std::string num(double x, bool json) {
  if (!std::isfinite(x)) return json ? "null" : (std::isnan(x) ? "nan" : "inf");
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string quoted(const std::string& s) {  // a JSON string
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

std::string csv_text(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::ofstream open(const std::filesystem::path& file) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream f(file);
  if (!f) throw std::runtime_error("cannot write " + file.string());
  return f;
}

template <class T, class F>
std::string json_list(const std::vector<T>& xs, F&& item) {
  std::string out = "[";
  for (size_t i = 0; i < xs.size(); ++i) out += (i ? ", " : "") + item(xs[i]);
  return out + "]";
}

std::string measurement_csv(const Measurement& m) {
  std::string rounds;  // "t1;t2;...": the interleaved rounds' CPU times, if re-timed
  for (double t : m.round_cpu) {
    if (!rounds.empty()) rounds += ';';
    rounds += num(t, false);
  }
  return std::to_string(m.steps) + "," + num(m.h, false) + "," + num(m.error, false) + "," +
         num(m.cpu, false) + "," + std::to_string(m.stats.grad_evals) + "," +
         std::to_string(m.stats.stage_iterations) + "," + csv_text(m.failure) + "," + rounds;
}

std::string measurement_json(const Measurement& m) {
  return "{\"steps\": " + std::to_string(m.steps) + ", \"h\": " + num(m.h, true) +
         ", \"error\": " + num(m.error, true) + ", \"cpu_seconds\": " + num(m.cpu, true) +
         ", \"grad_evals\": " + std::to_string(m.stats.grad_evals) +
         ", \"stage_iterations\": " + std::to_string(m.stats.stage_iterations) +
         ", \"failure\": " + quoted(m.failure) + ", \"round_cpu_seconds\": " +
         json_list(m.round_cpu, [](double t) { return num(t, true); }) + "}";
}

void write_csv(const std::filesystem::path& dir, const std::vector<ProblemResult>& problems) {
  std::ofstream sweep = open(dir / "sweep.csv"), energy = open(dir / "energy.csv");
  sweep << "problem,method,family,from_paper,order,steps,h,error,cpu_seconds,grad_evals,"
           "stage_iterations,failure,round_cpu_seconds\n";
  energy << "problem,method,family,h,t_end,max_energy_error,failure\n";
  for (const ProblemResult& p : problems)
    for (const MethodResult& m : p.methods) {
      const std::string head = p.key + "," + csv_text(m.name) + "," + family_key(m.family);
      for (const Measurement& x : m.sweep)
        sweep << head << "," << m.from_paper << "," << m.order << "," << measurement_csv(x) << "\n";
      for (size_t i = 0; i < m.energy.t_end.size(); ++i)
        energy << head << "," << num(m.energy.h, false) << "," << num(m.energy.t_end[i], false)
               << "," << num(m.energy.max_error[i], false) << "," << csv_text(m.energy.failure)
               << "\n";
    }
}

void write_scaling_csv(const std::filesystem::path& dir, const ScalingResult& s) {
  std::ofstream f = open(dir / "scaling.csv");
  f << "size,method,family,steps,h,error,cpu_seconds,grad_evals,stage_iterations,failure,"
       "round_cpu_seconds\n";
  for (const ScalingResult::Line& line : s.lines)
    for (size_t k = 0; k < line.brackets.size() && k < s.sizes.size(); ++k)
      for (const Measurement& x : line.brackets[k])
        f << s.sizes[k] << "," << csv_text(line.name) << "," << family_key(line.family) << ","
          << measurement_csv(x) << "\n";
}

std::string problem_json(const ProblemResult& p) {
  return "{\"key\": " + quoted(p.key) + ", \"title\": " + quoted(p.title) +
         ", \"t_error\": " + num(p.t_error, true) +
         ", \"reference\": {\"method\": " + quoted(p.reference.method) +
         ", \"accuracy\": " + num(p.reference.accuracy, true) + "}, \"methods\": " +
         json_list(p.methods,
                   [](const MethodResult& m) {
                     return "{\"name\": " + quoted(m.name) +
                            ", \"family\": " + quoted(family_key(m.family)) +
                            ", \"from_paper\": " + (m.from_paper ? "true" : "false") +
                            ", \"order\": " + std::to_string(m.order) +
                            ", \"sweep\": " + json_list(m.sweep, measurement_json) +
                            ", \"energy\": {\"h\": " + num(m.energy.h, true) + ", \"t_end\": " +
                            json_list(m.energy.t_end, [](double x) { return num(x, true); }) +
                            ", \"max_error\": " +
                            json_list(m.energy.max_error, [](double x) { return num(x, true); }) +
                            ", \"failure\": " + quoted(m.energy.failure) + "}}";
                   }) +
         "}";
}

std::string scaling_json(const ScalingResult& s) {
  return "{\"tolerances\": " + json_list(s.tolerances, [](double x) { return num(x, true); }) +
         ", \"t_end\": " + num(s.t_end, true) +
         ", \"sizes\": " + json_list(s.sizes, [](int n) { return std::to_string(n); }) +
         ", \"lines\": " +
         json_list(s.lines,
                   [](const ScalingResult::Line& l) {
                     return "{\"name\": " + quoted(l.name) +
                            ", \"family\": " + quoted(family_key(l.family)) + ", \"brackets\": " +
                            json_list(l.brackets,
                                      [](const std::vector<Measurement>& b) {
                                        return json_list(b, measurement_json);
                                      }) +
                            "}";
                   }) +
         "}";
}

}  // namespace

void write_raw_results(const std::filesystem::path& dir, const std::vector<ProblemResult>& problems,
                       const std::optional<ScalingResult>& scaling) {
  write_csv(dir, problems);
  if (scaling) write_scaling_csv(dir, *scaling);
  std::ofstream json = open(dir / "results.json");
  json << "{\"problems\": " << json_list(problems, problem_json)
       << ", \"scaling\": " << (scaling ? scaling_json(*scaling) : "null") << "}\n";
}

}  // namespace ex
