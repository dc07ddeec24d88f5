#pragma once
// A minimal SVG writer: shapes and text in pixel coordinates (origin top
// left, y down), collected in drawing order. Text is XML-escaped.
#include <string>
#include <vector>

namespace depot::eval {

struct Point2 {
  double x = 0.0;
  double y = 0.0;
};

enum class TextAnchor { kStart, kMiddle, kEnd };

struct Stroke {
  std::string colour = "#000000";
  double width = 1.0;
  std::string dash;  // SVG stroke-dasharray, empty for solid
};

struct TextStyle {
  double size = 12.0;
  TextAnchor anchor = TextAnchor::kStart;
  double rotate_deg = 0.0;  // about the anchor point
  bool bold = false;
  std::string colour = "#222222";
};

class SvgDocument {
 public:
  SvgDocument(double width, double height);

  void line(Point2 a, Point2 b, const Stroke& stroke);
  void polyline(const std::vector<Point2>& points, const Stroke& stroke);
  void rect(double x, double y, double width, double height, const std::string& fill,
            const Stroke* outline = nullptr);
  void circle(Point2 centre, double radius, const std::string& fill,
              const Stroke* outline = nullptr);
  void text(Point2 at, const std::string& content, const TextStyle& style = {});
  // A vertical gradient (bottom to top) through `colours`, usable as
  // fill="url(#id)".
  void vertical_gradient(const std::string& id, const std::vector<std::string>& colours);

  std::string str() const;

 private:
  double width_;
  double height_;
  std::string defs_;
  std::string body_;
};

std::string xml_escape(const std::string& text);

}  // namespace depot::eval
