#include "proxima/eval/plot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "proxima/core/error.h"
#include "proxima/eval/html_escape.h"

namespace proxima {
namespace {

// Colour-blind-safe qualitative palette (Okabe–Ito).
constexpr const char* kColors[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000",
                                   "#F0E442"};

std::string esc(const std::string& text) { return html_escape(text); }

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

std::string tick_label(double v) {
  if (v == 0.0) return "0";
  char buf[32];
  double a = std::fabs(v);
  if (a >= 1e7 || a < 1e-3) std::snprintf(buf, sizeof buf, "%.2g", v);
  else std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) hi = lo + 1.0;
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::floor(lo / step) * step; t <= hi + step * 1e-9; t += step)
    ticks.push_back(std::fabs(t) < step * 1e-9 ? 0.0 : t);
  if (ticks.size() < 2 || ticks.back() < hi - step * 1e-9) ticks.push_back(ticks.back() + step);
  return ticks;
}

std::string svg_chart(const Chart& c, int width, int height) {
  const bool bar = c.kind == Chart::Kind::Bar;
  const double left = 64, right = 150, top = 28, bottom = 46;  // legend on the right
  const double pw = width - left - right, ph = height - top - bottom;

  // y range over every finite (and, on a log axis, positive) value.
  double ylo = std::numeric_limits<double>::infinity(), yhi = -ylo;
  for (const ChartSeries& s : c.series)
    for (double v : s.y)
      if (std::isfinite(v) && (!c.log_y || v > 0.0)) {
        ylo = std::min(ylo, v);
        yhi = std::max(yhi, v);
      }
  if (!std::isfinite(ylo)) ylo = 0.0, yhi = 1.0;
  std::vector<double> yt;
  if (c.log_y) {
    double a = std::floor(std::log10(ylo)), b = std::ceil(std::log10(yhi));
    if (b <= a) b = a + 1;
    for (double e = a; e <= b; e += 1) yt.push_back(std::pow(10.0, e));
  } else {
    if (bar || ylo > 0.0) ylo = std::min(0.0, ylo);  // bars and positive data start at 0
    yt = nice_ticks(ylo, yhi);
  }
  const double y0 = yt.front(), y1 = yt.back();
  auto ymap = [&](double v) {
    double t = c.log_y ? (std::log10(v) - std::log10(y0)) / (std::log10(y1) - std::log10(y0)) : (v - y0) / (y1 - y0);
    return top + ph * (1.0 - t);
  };

  std::vector<double> xt;
  double x0 = 0, x1 = 1;
  if (!bar) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double v : c.x)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!std::isfinite(lo)) lo = 0, hi = 1;
    xt = nice_ticks(lo, hi);
    x0 = xt.front();
    x1 = xt.back();
  }
  auto xmap = [&](double v) { return left + pw * (v - x0) / (x1 - x0); };

  std::ostringstream o;
  o << "<svg class=\"chart\" width=\"" << width << "\" height=\"" << height << "\" viewBox=\"0 0 " << width << ' '
    << height << "\" role=\"img\" font-family=\"sans-serif\" font-size=\"11\">\n";
  o << "<title>" << esc(c.title) << "</title>\n";
  o << "<rect x=\"0\" y=\"0\" width=\"" << width << "\" height=\"" << height << "\" fill=\"white\"/>\n";
  o << "<text x=\"" << num(left + pw / 2) << "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\" font-weight=\"bold\">"
    << esc(c.title) << "</text>\n";
  // Grid and y ticks.
  for (double t : yt) {
    const double y = ymap(t);
    o << "<line x1=\"" << num(left) << "\" y1=\"" << num(y) << "\" x2=\"" << num(left + pw) << "\" y2=\"" << num(y)
      << "\" stroke=\"#e4e4e4\"/>\n<text x=\"" << num(left - 6) << "\" y=\"" << num(y + 4)
      << "\" text-anchor=\"end\">" << tick_label(t) << "</text>\n";
  }
  // Axes.
  o << "<line x1=\"" << num(left) << "\" y1=\"" << num(top) << "\" x2=\"" << num(left) << "\" y2=\"" << num(top + ph)
    << "\" stroke=\"#333\"/>\n<line x1=\"" << num(left) << "\" y1=\"" << num(top + ph) << "\" x2=\"" << num(left + pw)
    << "\" y2=\"" << num(top + ph) << "\" stroke=\"#333\"/>\n";
  o << "<text x=\"" << num(left + pw / 2) << "\" y=\"" << height - 8 << "\" text-anchor=\"middle\">" << esc(c.x_label)
    << "</text>\n";
  o << "<text transform=\"translate(14 " << num(top + ph / 2) << ") rotate(-90)\" text-anchor=\"middle\">"
    << esc(c.y_label) << "</text>\n";

  const size_t ns = c.series.size();
  if (bar) {
    const size_t nc = c.categories.size();
    const double group = nc ? pw / double(nc) : pw;
    const double bw = group * 0.8 / double(std::max<size_t>(1, ns));
    for (size_t k = 0; k < nc; ++k) {
      const double gx = left + group * double(k) + group * 0.1;
      o << "<text x=\"" << num(left + group * (double(k) + 0.5)) << "\" y=\"" << num(top + ph + 16)
        << "\" text-anchor=\"middle\">" << esc(c.categories[k]) << "</text>\n";
      for (size_t s = 0; s < ns; ++s) {
        if (k >= c.series[s].y.size()) continue;
        const double v = c.series[s].y[k];
        if (!std::isfinite(v) || (c.log_y && v <= 0.0)) continue;
        const double base = c.log_y ? top + ph : ymap(std::max(0.0, y0));
        const double y = ymap(v);
        o << "<rect x=\"" << num(gx + bw * double(s)) << "\" y=\"" << num(std::min(y, base)) << "\" width=\""
          << num(bw * 0.92) << "\" height=\"" << num(std::fabs(base - y)) << "\" fill=\"" << kColors[s % 8]
          << "\"><title>" << esc(c.series[s].name) << ", " << esc(c.categories[k]) << ": " << tick_label(v)
          << "</title></rect>\n";
      }
    }
  } else {
    for (double t : xt)
      o << "<text x=\"" << num(xmap(t)) << "\" y=\"" << num(top + ph + 16) << "\" text-anchor=\"middle\">"
        << tick_label(t) << "</text>\n<line x1=\"" << num(xmap(t)) << "\" y1=\"" << num(top + ph) << "\" x2=\""
        << num(xmap(t)) << "\" y2=\"" << num(top + ph + 4) << "\" stroke=\"#333\"/>\n";
    for (size_t s = 0; s < ns; ++s) {
      const char* color = kColors[s % 8];
      std::string path;
      bool pen = false;
      std::ostringstream marks;
      for (size_t i = 0; i < c.x.size() && i < c.series[s].y.size(); ++i) {
        const double v = c.series[s].y[i];
        if (!std::isfinite(v) || !std::isfinite(c.x[i]) || (c.log_y && v <= 0.0)) {
          pen = false;  // a gap
          continue;
        }
        path += (pen ? " L" : " M") + num(xmap(c.x[i])) + " " + num(ymap(v));
        pen = true;
        marks << "<circle cx=\"" << num(xmap(c.x[i])) << "\" cy=\"" << num(ymap(v)) << "\" r=\"3\" fill=\"" << color
              << "\"><title>" << esc(c.series[s].name) << ": " << tick_label(c.x[i]) << ", " << tick_label(v)
              << "</title></circle>\n";
      }
      if (!path.empty())
        o << "<path d=\"" << path.substr(1) << "\" fill=\"none\" stroke=\"" << color << "\" stroke-width=\"2\"/>\n";
      o << marks.str();
    }
  }
  // Legend.
  for (size_t s = 0; s < ns; ++s) {
    const double y = top + 8 + 18 * double(s);
    o << "<rect x=\"" << num(left + pw + 14) << "\" y=\"" << num(y - 8) << "\" width=\"12\" height=\"10\" fill=\""
      << kColors[s % 8] << "\"/>\n<text x=\"" << num(left + pw + 32) << "\" y=\"" << num(y + 1) << "\">"
      << esc(c.series[s].name) << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

Chart chart_from_table(const PlotSpec& spec, const Table& table) {
  auto column = [&](const std::string& name) {
    auto it = std::find(table.columns.begin(), table.columns.end(), name);
    if (it == table.columns.end()) fail_input("plot '" + spec.title + "': table '" + table.title + "' has no column '" + name + "'");
    return size_t(it - table.columns.begin());
  };
  auto number = [](const std::variant<std::string, double>& cell) {
    const double* d = std::get_if<double>(&cell);
    return d ? *d : std::nan("");
  };
  Chart c;
  c.kind = spec.kind == "bar" ? Chart::Kind::Bar : Chart::Kind::Line;
  c.title = spec.title;
  c.x_label = spec.x_label.empty() ? spec.x : spec.x_label;
  c.y_label = spec.y_label;
  c.log_y = spec.log_y;
  const size_t xi = column(spec.x);
  for (const auto& row : table.rows) {
    if (xi >= row.size()) continue;
    if (c.kind == Chart::Kind::Bar) c.categories.push_back(format_cell(row[xi]));
    else c.x.push_back(number(row[xi]));
  }
  for (const std::string& name : spec.y) {
    const size_t yi = column(name);
    ChartSeries s{name, {}};
    for (const auto& row : table.rows)
      if (xi < row.size()) s.y.push_back(yi < row.size() ? number(row[yi]) : std::nan(""));
    c.series.push_back(std::move(s));
  }
  return c;
}

}  // namespace proxima
