#include "eval/svg_document.h"

#include "common/number_text.h"

// Coordinates are written with two decimals (fixed_number(v, 2)): sub-pixel
// exact, compact files.

namespace depot::eval {
namespace {

std::string stroke_attributes(const Stroke& s) {
  std::string out =
      " stroke=\"" + s.colour + "\" stroke-width=\"" + fixed_number(s.width, 2) + "\"";
  if (!s.dash.empty()) out += " stroke-dasharray=\"" + s.dash + "\"";
  return out;
}

const char* anchor_name(TextAnchor a) {
  switch (a) {
    case TextAnchor::kStart:
      return "start";
    case TextAnchor::kMiddle:
      return "middle";
    case TextAnchor::kEnd:
      return "end";
  }
  return "start";
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

SvgDocument::SvgDocument(double width, double height) : width_(width), height_(height) {}

void SvgDocument::line(Point2 a, Point2 b, const Stroke& stroke) {
  body_ += "<line x1=\"" + fixed_number(a.x, 2) + "\" y1=\"" + fixed_number(a.y, 2) + "\" x2=\"" +
           fixed_number(b.x, 2) + "\" y2=\"" + fixed_number(b.y, 2) + "\"" +
           stroke_attributes(stroke) + "/>\n";
}

void SvgDocument::polyline(const std::vector<Point2>& points, const Stroke& stroke) {
  if (points.size() < 2) return;
  body_ += "<polyline fill=\"none\" stroke-linejoin=\"round\"" + stroke_attributes(stroke) +
           " points=\"";
  for (size_t k = 0; k < points.size(); ++k) {
    if (k > 0) body_ += ' ';
    body_ += fixed_number(points[k].x, 2) + "," + fixed_number(points[k].y, 2);
  }
  body_ += "\"/>\n";
}

void SvgDocument::rect(double x, double y, double width, double height, const std::string& fill,
                       const Stroke* outline) {
  body_ += "<rect x=\"" + fixed_number(x, 2) + "\" y=\"" + fixed_number(y, 2) + "\" width=\"" +
           fixed_number(width, 2) + "\" height=\"" + fixed_number(height, 2) + "\" fill=\"" + fill +
           "\"" + (outline ? stroke_attributes(*outline) : std::string()) + "/>\n";
}

void SvgDocument::circle(Point2 centre, double radius, const std::string& fill,
                         const Stroke* outline) {
  body_ += "<circle cx=\"" + fixed_number(centre.x, 2) + "\" cy=\"" + fixed_number(centre.y, 2) +
           "\" r=\"" + fixed_number(radius, 2) + "\" fill=\"" + fill + "\"" +
           (outline ? stroke_attributes(*outline) : std::string()) + "/>\n";
}

void SvgDocument::text(Point2 at, const std::string& content, const TextStyle& style) {
  body_ += "<text x=\"" + fixed_number(at.x, 2) + "\" y=\"" + fixed_number(at.y, 2) +
           "\" font-size=\"" + fixed_number(style.size, 2) + "\" text-anchor=\"" +
           anchor_name(style.anchor) + "\" fill=\"" + style.colour + "\"";
  if (style.bold) body_ += " font-weight=\"bold\"";
  if (style.rotate_deg != 0.0) {
    body_ += " transform=\"rotate(" + fixed_number(style.rotate_deg, 2) + " " +
             fixed_number(at.x, 2) + " " + fixed_number(at.y, 2) + ")\"";
  }
  body_ += ">" + xml_escape(content) + "</text>\n";
}

void SvgDocument::vertical_gradient(const std::string& id,
                                    const std::vector<std::string>& colours) {
  defs_ += "<linearGradient id=\"" + id + "\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">\n";
  for (size_t k = 0; k < colours.size(); ++k) {
    const double offset = colours.size() > 1 ? static_cast<double>(k) / (colours.size() - 1) : 0.0;
    defs_ +=
        "  <stop offset=\"" + fixed_number(offset, 2) + "\" stop-color=\"" + colours[k] + "\"/>\n";
  }
  defs_ += "</linearGradient>\n";
}

std::string SvgDocument::str() const {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fixed_number(width_, 2) +
         "\" height=\"" + fixed_number(height_, 2) + "\" viewBox=\"0 0 " + fixed_number(width_, 2) +
         " " + fixed_number(height_, 2) +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
  if (!defs_.empty()) out += "<defs>\n" + defs_ + "</defs>\n";
  out += "<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  out += body_;
  out += "</svg>\n";
  return out;
}

}  // namespace depot::eval
