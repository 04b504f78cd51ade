// A minimal SVG line chart (linear axes), written directly: no plotting program is started.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace erkn::scaling {

struct Series {
  std::string label, color;
  std::vector<double> x, y;
  bool dashed = false;
};

struct Chart {
  std::string title, xlabel, ylabel;
  std::vector<Series> series;
};

/// Writes the chart to path (axes from 0 to the largest x and y, rounded up); throws
/// std::runtime_error if the file cannot be written.
void write_svg(const Chart& chart, const std::filesystem::path& path);

}  // namespace erkn::scaling
