#include "eval/svg_document.h"

#include <fmt/format.h>

namespace depot::eval {
namespace {

// Coordinates with two decimals: sub-pixel exact, compact files.
std::string num(double v) {
  return fmt::format("{:.2f}", v);
}

std::string stroke_attributes(const Stroke& s) {
  std::string out = " stroke=\"" + s.colour + "\" stroke-width=\"" + num(s.width) + "\"";
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
  body_ += "<line x1=\"" + num(a.x) + "\" y1=\"" + num(a.y) + "\" x2=\"" + num(b.x) + "\" y2=\"" +
           num(b.y) + "\"" + stroke_attributes(stroke) + "/>\n";
}

void SvgDocument::polyline(const std::vector<Point2>& points, const Stroke& stroke) {
  if (points.size() < 2) return;
  body_ += "<polyline fill=\"none\" stroke-linejoin=\"round\"" + stroke_attributes(stroke) +
           " points=\"";
  for (size_t k = 0; k < points.size(); ++k) {
    if (k > 0) body_ += ' ';
    body_ += num(points[k].x) + "," + num(points[k].y);
  }
  body_ += "\"/>\n";
}

void SvgDocument::rect(double x, double y, double width, double height, const std::string& fill,
                       const Stroke* outline) {
  body_ += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(width) +
           "\" height=\"" + num(height) + "\" fill=\"" + fill + "\"" +
           (outline ? stroke_attributes(*outline) : std::string()) + "/>\n";
}

void SvgDocument::circle(Point2 centre, double radius, const std::string& fill,
                         const Stroke* outline) {
  body_ += "<circle cx=\"" + num(centre.x) + "\" cy=\"" + num(centre.y) + "\" r=\"" + num(radius) +
           "\" fill=\"" + fill + "\"" + (outline ? stroke_attributes(*outline) : std::string()) +
           "/>\n";
}

void SvgDocument::text(Point2 at, const std::string& content, const TextStyle& style) {
  body_ += "<text x=\"" + num(at.x) + "\" y=\"" + num(at.y) + "\" font-size=\"" + num(style.size) +
           "\" text-anchor=\"" + anchor_name(style.anchor) + "\" fill=\"" + style.colour + "\"";
  if (style.bold) body_ += " font-weight=\"bold\"";
  if (style.rotate_deg != 0.0) {
    body_ +=
        " transform=\"rotate(" + num(style.rotate_deg) + " " + num(at.x) + " " + num(at.y) + ")\"";
  }
  body_ += ">" + xml_escape(content) + "</text>\n";
}

void SvgDocument::vertical_gradient(const std::string& id,
                                    const std::vector<std::string>& colours) {
  defs_ += "<linearGradient id=\"" + id + "\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">\n";
  for (size_t k = 0; k < colours.size(); ++k) {
    const double offset = colours.size() > 1 ? static_cast<double>(k) / (colours.size() - 1) : 0.0;
    defs_ += "  <stop offset=\"" + num(offset) + "\" stop-color=\"" + colours[k] + "\"/>\n";
  }
  defs_ += "</linearGradient>\n";
}

std::string SvgDocument::str() const {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width_) + "\" height=\"" +
         num(height_) + "\" viewBox=\"0 0 " + num(width_) + " " + num(height_) +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
  if (!defs_.empty()) out += "<defs>\n" + defs_ + "</defs>\n";
  out += "<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  out += body_;
  out += "</svg>\n";
  return out;
}

}  // namespace depot::eval
