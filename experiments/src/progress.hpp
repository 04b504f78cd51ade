// A one-line progress bar on stdout, drawn only when stdout is a terminal; it also keeps the
// wall time of every unit of work, so a run can say where its time went.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace ex {

class Progress {
 public:
  explicit Progress(long total);
  ~Progress();
  /// Marks one unit of work done; `label` names the next one.
  void advance(const std::string& label);
  void label(const std::string& label);
  /// Records the wall time since the last record under `unit` without advancing the bar.
  void record(const std::string& unit);
  /// Ends the bar's line (before other output).
  void finish();
  /// Wall seconds of each unit of work so far, named by the label passed to advance().
  const std::vector<std::pair<std::string, double>>& unit_seconds() const { return units_; }
  /// Writes unit_seconds() to `file` as CSV (unit, seconds), slowest first.
  void write_unit_seconds(const std::filesystem::path& file) const;

 private:
  void draw();
  long total_, done_ = 0;
  std::string label_;
  bool enabled_, drawn_ = false;
  double start_, unit_start_;
  std::vector<std::pair<std::string, double>> units_;
};

}  // namespace ex
