#include "cosim/reports/html.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cosim/reports/junit.hpp"
#include "cosim/reports/text.hpp"

namespace voxcast::cosim::html {
namespace {

// Plot-area geometry of the charts, in SVG user units.
constexpr double kWidth = 640, kHeight = 400, kLeft = 70, kRight = 20, kTop = 30, kBottom = 50;

struct Axis {
  double lo, hi;
  double at(double v, double from, double to) const {
    return hi > lo ? from + (v - lo) / (hi - lo) * (to - from) : (from + to) / 2;
  }
};

Axis padded(double lo, double hi) {
  const double pad = hi > lo ? (hi - lo) * 0.06 : std::max(1.0, std::abs(lo) * 0.1);
  return {lo - pad, hi + pad};
}

std::string svg_open(const std::string& title) {
  return "<figure><svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " +
         fixed_text(kWidth, 0) + " " + fixed_text(kHeight, 0) + "\" width=\"" +
         fixed_text(kWidth, 0) + "\" height=\"" + fixed_text(kHeight, 0) +
         "\" role=\"img\" aria-label=\"" + escape(title) + "\">" + "<rect x=\"" +
         fixed_text(kLeft) + "\" y=\"" + fixed_text(kTop) + "\" width=\"" +
         fixed_text(kWidth - kLeft - kRight) + "\" height=\"" +
         fixed_text(kHeight - kTop - kBottom) + "\" fill=\"#fafafa\" stroke=\"#999\"/>";
}

std::string svg_close(const std::string& title) {
  return "</svg><figcaption>" + escape(title) + "</figcaption></figure>\n";
}

}  // namespace

std::string escape(const std::string& text) {
  const std::string safe = xml_safe_text(text);
  std::string out;
  out.reserve(safe.size());
  for (char c : safe) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string file_url(const std::string& file_name) {
  static const char* hex = "0123456789ABCDEF";
  std::string out = "./";
  for (unsigned char c : file_name) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

std::string page(const std::string& title, const std::string& body) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
         escape(title) +
         "</title>\n<style>\n"
         "body { font-family: sans-serif; margin: 1.5em; color: #222; }\n"
         "table { border-collapse: collapse; margin: 0.5em 0 1.5em; }\n"
         "th, td { border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: left; }\n"
         "th { background: #eee; }\n"
         "figure { display: inline-block; margin: 0 1em 1em 0; vertical-align: top; }\n"
         "figcaption { font-size: 0.9em; color: #555; }\n"
         "img { image-rendering: pixelated; border: 1px solid #ccc; }\n"
         ".pass { color: #060; font-weight: bold; } .fail { color: #a00; font-weight: bold; }\n"
         ".skip { color: #a60; font-weight: bold; }\n"
         "</style>\n</head>\n<body>\n<h1>" +
         escape(title) + "</h1>\n" + body +
         // Each image records the size it loaded at (0x0: it did not load), so
         // a headless browser's DOM dump shows what a reader saw (the test
         // Html.ChromiumRendersTheCosimPage).
         "<script>\nwindow.addEventListener('load', function () {\n"
         "  for (var i = 0; i < document.images.length; ++i) {\n"
         "    var img = document.images[i];\n"
         "    img.setAttribute('data-loaded', img.naturalWidth + 'x' + img.naturalHeight);\n"
         "  }\n});\n</script>\n</body>\n</html>\n";
}

std::string table(const std::vector<std::string>& head,
                  const std::vector<std::vector<std::string>>& rows) {
  std::string out = "<table>\n<tr>";
  for (const std::string& h : head) out += "<th>" + escape(h) + "</th>";
  out += "</tr>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const std::string& c : row) out += "<td>" + escape(c) + "</td>";
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

std::string figure(const std::string& file_name, const std::string& caption, int width,
                   int height, int scale) {
  return "<figure><img src=\"" + escape(file_url(file_name)) + "\" width=\"" +
         std::to_string(width * scale) + "\" height=\"" + std::to_string(height * scale) +
         "\" alt=\"" + escape(caption) + "\"><figcaption>" + escape(caption) +
         "</figcaption></figure>\n";
}

std::string bar_chart(const std::string& title, const std::vector<std::string>& labels,
                      const std::vector<double>& values, const std::string& value_unit) {
  std::string out = svg_open(title);
  const double top = values.empty() ? 1.0 : std::max(1.0, *std::max_element(values.begin(), values.end()));
  const double slot =
      (kWidth - kLeft - kRight) / static_cast<double>(std::max<std::size_t>(1, values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double h = values[i] / top * (kHeight - kTop - kBottom);
    const double x = kLeft + slot * static_cast<double>(i) + slot * 0.15;
    out += "<rect x=\"" + fixed_text(x) + "\" y=\"" + fixed_text(kHeight - kBottom - h) +
           "\" width=\"" + fixed_text(slot * 0.7) + "\" height=\"" + fixed_text(h) +
           "\" fill=\"#4a7ab5\"><title>" +
           escape(labels[i] + ": " + fixed_text(values[i], 0) + " " + value_unit) +
           "</title></rect>";
    out += "<text x=\"" + fixed_text(x + slot * 0.35) + "\" y=\"" +
           fixed_text(kHeight - kBottom + 16) + "\" font-size=\"11\" text-anchor=\"middle\">" +
           escape(labels[i]) + "</text>";
    out += "<text x=\"" + fixed_text(x + slot * 0.35) + "\" y=\"" +
           fixed_text(kHeight - kBottom - h - 4) + "\" font-size=\"11\" text-anchor=\"middle\">" +
           fixed_text(values[i], 0) + "</text>";
  }
  out += "<text x=\"" + fixed_text(kLeft) + "\" y=\"" + fixed_text(kTop - 10) +
         "\" font-size=\"12\">" + escape(value_unit) + "</text>";
  return out + svg_close(title);
}

std::string scatter(const std::string& title, const std::string& x_label,
                    const std::string& y_label, const std::vector<ScatterPoint>& points) {
  std::string out = svg_open(title);
  if (points.empty()) return out + svg_close(title + " (no point to plot)");
  double x0 = points[0].x, x1 = x0, y0 = points[0].y, y1 = y0;
  for (const ScatterPoint& p : points) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  const Axis ax = padded(x0, x1), ay = padded(y0, y1);
  const auto px = [&](double v) { return ax.at(v, kLeft, kWidth - kRight); };
  const auto py = [&](double v) { return ay.at(v, kHeight - kBottom, kTop); };
  // Ticks: the extremes of the data on each axis.
  for (double v : {x0, x1})
    out += "<text x=\"" + fixed_text(px(v)) + "\" y=\"" + fixed_text(kHeight - kBottom + 16) +
           "\" font-size=\"11\" text-anchor=\"middle\">" + fixed_text(v, 3) + "</text>";
  for (double v : {y0, y1})
    out += "<text x=\"" + fixed_text(kLeft - 6) + "\" y=\"" + fixed_text(py(v) + 4) +
           "\" font-size=\"11\" text-anchor=\"end\">" + fixed_text(v, 2) + "</text>";
  out += "<text x=\"" + fixed_text((kLeft + kWidth - kRight) / 2) + "\" y=\"" +
         fixed_text(kHeight - 12) + "\" font-size=\"12\" text-anchor=\"middle\">" +
         escape(x_label) + "</text>";
  out += "<text x=\"14\" y=\"" + fixed_text((kTop + kHeight - kBottom) / 2) +
         "\" font-size=\"12\" text-anchor=\"middle\" transform=\"rotate(-90 14 " +
         fixed_text((kTop + kHeight - kBottom) / 2) + ")\">" + escape(y_label) + "</text>";
  // The front: its points joined in x order.
  std::vector<ScatterPoint> front;
  for (const ScatterPoint& p : points)
    if (p.front) front.push_back(p);
  std::sort(front.begin(), front.end(),
            [](const ScatterPoint& a, const ScatterPoint& b) { return a.x < b.x; });
  if (front.size() > 1) {
    out += "<polyline fill=\"none\" stroke=\"#c33\" stroke-width=\"2\" points=\"";
    for (const ScatterPoint& p : front)
      out += fixed_text(px(p.x)) + "," + fixed_text(py(p.y)) + " ";
    out += "\"/>";
  }
  for (const ScatterPoint& p : points) {
    out += "<circle class=\"point\" cx=\"" + fixed_text(px(p.x)) + "\" cy=\"" +
           fixed_text(py(p.y)) + "\" r=\"4\" fill=\"#4a7ab5\"" +
           (p.front ? " stroke=\"#c33\" stroke-width=\"3\"" : "") + "><title>" +
           escape(p.label + (p.front ? " (on the front)" : "")) + "</title></circle>";
    out += "<text class=\"label\" x=\"" + fixed_text(px(p.x) + 6) + "\" y=\"" +
           fixed_text(py(p.y) - 6) + "\" font-size=\"10\">" + escape(p.label) + "</text>";
  }
  return out + svg_close(title + " (ringed and joined: the Pareto front)");
}

}  // namespace voxcast::cosim::html
