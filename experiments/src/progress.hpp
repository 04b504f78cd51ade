// A one-line progress bar on stdout, drawn only when stdout is a terminal.
#pragma once

#include <string>

namespace ex {

class Progress {
 public:
  explicit Progress(long total);
  ~Progress();
  /// Marks one unit of work done; `label` names the next one.
  void advance(const std::string& label);
  void label(const std::string& label);
  /// Ends the bar's line (before other output).
  void finish();

 private:
  void draw();
  long total_, done_ = 0;
  std::string label_;
  bool enabled_, drawn_ = false;
  double start_;
};

}  // namespace ex
