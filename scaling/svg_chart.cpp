#include "svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace erkn::scaling {
namespace {

constexpr double kWidth = 720, kHeight = 460, kLeft = 70, kRight = 190, kTop = 40, kBottom = 60;

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s)
    out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

// The smallest of 1, 2, 5 times a power of ten that is >= x.
double nice_ceiling(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= x * (1 - 1e-12)) return m * p;
  return 10 * p;
}

}  // namespace

void write_svg(const Chart& chart, const std::filesystem::path& path) {
  double xmax = 0, ymax = 0;
  for (const Series& s : chart.series) {
    for (double x : s.x) xmax = std::max(xmax, x);
    for (double y : s.y) ymax = std::max(ymax, y);
  }
  xmax = nice_ceiling(std::max(xmax, 1e-300));
  ymax = nice_ceiling(std::max(ymax, 1e-300));
  const double w = kWidth - kLeft - kRight, h = kHeight - kTop - kBottom;
  const auto X = [&](double x) { return kLeft + w * x / xmax; };
  const auto Y = [&](double y) { return kTop + h * (1 - y / ymax); };
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidth << "' height='" << kHeight
      << "' font-family='DejaVu Sans, sans-serif' font-size='12'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << kLeft + w / 2 << "' y='22' text-anchor='middle' font-size='14'>"
      << escaped(chart.title) << "</text>\n";
  for (int k = 0; k <= 5; ++k) {  // grid and tick labels
    const double xv = xmax * k / 5, yv = ymax * k / 5;
    svg << "<line x1='" << X(xv) << "' y1='" << kTop << "' x2='" << X(xv) << "' y2='" << kTop + h
        << "' stroke='#dddddd'/>\n<text x='" << X(xv) << "' y='" << kTop + h + 18
        << "' text-anchor='middle'>" << xv << "</text>\n"
        << "<line x1='" << kLeft << "' y1='" << Y(yv) << "' x2='" << kLeft + w << "' y2='" << Y(yv)
        << "' stroke='#dddddd'/>\n<text x='" << kLeft - 8 << "' y='" << Y(yv) + 4
        << "' text-anchor='end'>" << yv << "</text>\n";
  }
  svg << "<rect x='" << kLeft << "' y='" << kTop << "' width='" << w << "' height='" << h
      << "' fill='none' stroke='black'/>\n"
      << "<text x='" << kLeft + w / 2 << "' y='" << kHeight - 15 << "' text-anchor='middle'>"
      << escaped(chart.xlabel) << "</text>\n"
      << "<text transform='translate(18," << kTop + h / 2 << ") rotate(-90)' text-anchor='middle'>"
      << escaped(chart.ylabel) << "</text>\n";
  for (std::size_t k = 0; k < chart.series.size(); ++k) {
    const Series& s = chart.series[k];
    svg << "<polyline fill='none' stroke='" << s.color << "' stroke-width='2'"
        << (s.dashed ? " stroke-dasharray='6,4'" : "") << " points='";
    for (std::size_t i = 0; i < s.x.size(); ++i) svg << X(s.x[i]) << ',' << Y(s.y[i]) << ' ';
    svg << "'/>\n";
    for (std::size_t i = 0; i < s.x.size() && !s.dashed; ++i)
      svg << "<circle cx='" << X(s.x[i]) << "' cy='" << Y(s.y[i]) << "' r='3.5' fill='" << s.color
          << "'/>\n";
    const double ly = kTop + 10 + 20 * double(k);
    svg << "<line x1='" << kLeft + w + 12 << "' y1='" << ly << "' x2='" << kLeft + w + 36
        << "' y2='" << ly << "' stroke='" << s.color << "' stroke-width='2'"
        << (s.dashed ? " stroke-dasharray='6,4'" : "") << "/>\n<text x='" << kLeft + w + 42
        << "' y='" << ly + 4 << "'>" << escaped(s.label) << "</text>\n";
  }
  svg << "</svg>\n";
  std::ofstream out(path);
  if (!(out << svg.str())) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace erkn::scaling
