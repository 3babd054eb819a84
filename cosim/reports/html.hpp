// Self-contained HTML report pages (cosim --html, sweep --html): one file a
// hardware engineer opens in a browser, as Vitis HLS and hls4ml users read one
// synthesis report page. No network: the style is inline, the charts are
// inline SVG, and the images are the PNG files written beside the page,
// referenced by relative name.
//
// Every piece of text that reaches a page goes through escape(): scene and
// file names are user data, and may hold markup or bytes that are not UTF-8.
#pragma once

#include <string>
#include <vector>

namespace voxcast::cosim::html {

// `text` as HTML character data or a quoted attribute value: invalid UTF-8
// and control characters become U+FFFD (xml_safe_text), & < > " ' entities.
std::string escape(const std::string& text);

// A relative URL for a file beside the page: its name percent-encoded
// (RFC 3986 unreserved characters kept), so a name with spaces, quotes or
// non-ASCII bytes still loads.
std::string file_url(const std::string& file_name);

// <!DOCTYPE html> ... with `title` (escaped) and `body` (HTML, not escaped).
std::string page(const std::string& title, const std::string& body);

// A table: `head` and every cell escaped.
std::string table(const std::vector<std::string>& head,
                  const std::vector<std::vector<std::string>>& rows);

// An image beside the page, shown at its pixel size scaled by `scale`, with a caption.
std::string figure(const std::string& file_name, const std::string& caption, int width,
                   int height, int scale = 1);

// A bar chart (inline SVG): one bar per label, heights proportional to values.
std::string bar_chart(const std::string& title, const std::vector<std::string>& labels,
                      const std::vector<double>& values, const std::string& value_unit);

// A scatter plot (inline SVG) with every point labelled, the points on the
// front ringed and joined in x order. Points must be finite (a sweep leaves
// out the points whose PSNR is infinite: no error at all).
struct ScatterPoint {
  double x = 0.0, y = 0.0;
  std::string label;
  bool front = false;
};
std::string scatter(const std::string& title, const std::string& x_label,
                    const std::string& y_label, const std::vector<ScatterPoint>& points);

}  // namespace voxcast::cosim::html
