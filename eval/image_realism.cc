#include "eval/image_realism.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "common/error.h"
#include "eval/series_plot.h"

namespace depot::eval {

namespace {

constexpr double kMinNoisePixels = 200;  // per bin and recording

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double x = p * (v.size() - 1);
  const size_t i = static_cast<size_t>(std::floor(x));
  const double a = x - i;
  return i + 1 < v.size() ? (1 - a) * v[i] + a * v[i + 1] : v[i];
}

void measure_noise(const cv::Mat& grey, FrameRealism& out) {
  // Immerkaer (1996): the 3x3 operator N cancels planes and lines, so on a
  // smooth patch |I * N| is noise alone; sigma = sqrt(pi/2) / 6 x mean|I * N|.
  static const cv::Mat kernel = (cv::Mat_<float>(3, 3) << 1, -2, 1, -2, 4, -2, 1, -2, 1);
  cv::Mat f, response, mean, gx, gy;
  grey.convertTo(f, CV_32F);
  cv::filter2D(f, response, CV_32F, kernel);
  cv::blur(f, mean, cv::Size(3, 3));
  cv::Sobel(f, gx, CV_32F, 1, 0);
  cv::Sobel(f, gy, CV_32F, 0, 1);
  for (int y = 1; y + 1 < f.rows; ++y) {
    const float* r = response.ptr<float>(y);
    const float* m = mean.ptr<float>(y);
    const float* ax = gx.ptr<float>(y);
    const float* ay = gy.ptr<float>(y);
    for (int x = 1; x + 1 < f.cols; ++x) {
      // Smooth: the Sobel gradient (about 8x the per-pixel slope) stays
      // below what noise alone of a few grey levels gives.
      if (std::abs(ax[x]) + std::abs(ay[x]) > 40.0f) continue;
      const int bin = std::clamp(static_cast<int>(m[x] / (256.0 / kNoiseBins)), 0, kNoiseBins - 1);
      out.noise_sum[bin] += std::abs(r[x]);
      out.noise_count[bin] += 1;
    }
  }
}

void measure_keypoints(const cv::Mat& grey, FrameRealism& out) {
  auto orb = cv::ORB::create(20000, 1.2f, 8, 31, 0, 2, cv::ORB::FAST_SCORE, 31, 20);
  std::vector<cv::KeyPoint> keypoints;
  orb->detect(grey, keypoints);
  out.keypoints = static_cast<int>(keypoints.size());
  std::vector<double> responses;
  for (const auto& k : keypoints) responses.push_back(k.response);
  out.response_median = responses.empty() ? 0.0 : percentile(responses, 0.5);
}

void measure_depth(const cv::Mat& depth, FrameRealism& out) {
  out.has_depth = true;
  const size_t bins = kHoleDepthEdges.size();
  out.holes_by_depth.assign(bins, 0.0);
  out.pixels_by_depth.assign(bins, 0.0);
  cv::Mat valid = depth > 0;
  cv::Mat high = depth.clone(), low = depth.clone();
  low.setTo(1e9, ~valid);
  const cv::Mat window = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5));
  cv::Mat local_max, local_min;
  cv::dilate(high, local_max, window);
  cv::erode(low, local_min, window);
  // Local mean depth of the valid neighbours: where a hole would have been.
  cv::Mat valid_f, sum, count;
  valid.convertTo(valid_f, CV_32F, 1.0 / 255.0);
  cv::boxFilter(depth, sum, CV_32F, cv::Size(7, 7), cv::Point(-1, -1), false);
  cv::boxFilter(valid_f, count, CV_32F, cv::Size(7, 7), cv::Point(-1, -1), false);
  for (int y = 0; y < depth.rows; ++y) {
    const float* d = depth.ptr<float>(y);
    const float* hi = local_max.ptr<float>(y);
    const float* lo = local_min.ptr<float>(y);
    const float* s = sum.ptr<float>(y);
    const float* c = count.ptr<float>(y);
    for (int x = 0; x < depth.cols; ++x) {
      const bool hole = d[x] <= 0.0f;
      out.pixels += 1;
      out.holes += hole;
      // A depth edge: neighbours 5x5 apart by more than 10 cm plus 5 %.
      if (lo[x] < 1e8f && hi[x] - lo[x] > 0.1f + 0.05f * lo[x]) {
        out.edge_pixels += 1;
        out.edge_holes += hole;
      }
      if (c[x] <= 0.0f) continue;
      const double z = s[x] / c[x];
      size_t bin = bins - 1;
      while (bin > 0 && z < kHoleDepthEdges[bin]) --bin;
      out.pixels_by_depth[bin] += 1;
      out.holes_by_depth[bin] += hole;
    }
  }
}

double measure_motion(const cv::Mat& previous, const cv::Mat& grey) {
  std::vector<cv::Point2f> corners, moved;
  cv::goodFeaturesToTrack(previous, corners, 300, 0.01, 8);
  if (corners.size() < 10) return -1;
  std::vector<uchar> status;
  std::vector<float> error;
  cv::calcOpticalFlowPyrLK(previous, grey, corners, moved, status, error, cv::Size(21, 21), 3);
  std::vector<double> d;
  for (size_t i = 0; i < corners.size(); ++i)
    if (status[i]) d.push_back(cv::norm(moved[i] - corners[i]));
  return d.size() < 10 ? -1 : percentile(d, 0.5);
}

std::string figure(double v) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream o;
  if (std::abs(v) >= 100)
    o << std::fixed << std::setprecision(0) << v;
  else
    o << std::setprecision(3) << v;
  return o.str();
}

std::string ratio(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b) || b == 0) return "-";
  std::ostringstream o;
  o << std::fixed << std::setprecision(2) << a / b << "x";
  return o.str();
}

struct Row {
  std::string name;
  double simulated, reference;
};

std::vector<Row> rows(const Realism& s, const Realism& r) {
  std::vector<Row> out = {
      {"frames", static_cast<double>(s.frames), static_cast<double>(r.frames)},
      {"sharpness p10 (Laplacian variance)", s.sharpness_p10, r.sharpness_p10},
      {"sharpness median", s.sharpness_median, r.sharpness_median},
      {"sharpness p90", s.sharpness_p90, r.sharpness_p90},
  };
  for (int b = 0; b < kNoiseBins; ++b) {
    const int lo = b * 256 / kNoiseBins, hi = (b + 1) * 256 / kNoiseBins - 1;
    out.push_back({"noise sigma, grey " + std::to_string(lo) + "-" + std::to_string(hi),
                   s.noise_sigma[b], r.noise_sigma[b]});
  }
  out.push_back({"ORB keypoints median", s.keypoints_median, r.keypoints_median});
  out.push_back({"ORB FAST response median", s.response_median, r.response_median});
  out.push_back({"depth holes (share of pixels)", s.hole_share, r.hole_share});
  out.push_back({"depth holes at depth edges", s.edge_hole_share, r.edge_hole_share});
  for (size_t b = 0; b < kHoleDepthEdges.size(); ++b)
    out.push_back({"depth holes near " + depth_bin_name(b), s.hole_share_by_depth[b],
                   r.hole_share_by_depth[b]});
  out.push_back({"image motion median (px a frame)", s.motion_median, r.motion_median});
  return out;
}

}  // namespace

std::string depth_bin_name(size_t b) {
  std::ostringstream o;
  o << kHoleDepthEdges[b];
  if (b + 1 < kHoleDepthEdges.size())
    o << "-" << kHoleDepthEdges[b + 1] << " m";
  else
    o << "+ m";
  return o.str();
}

FrameRealism measure_frame(const cv::Mat& bgr, const cv::Mat& depth, const cv::Mat& previous_grey) {
  if (bgr.empty() || bgr.type() != CV_8UC3) fail("realism", "colour image must be 8-bit BGR");
  FrameRealism out;
  cv::Mat grey, laplacian;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::Laplacian(grey, laplacian, CV_64F);
  cv::Scalar mean, sd;
  cv::meanStdDev(laplacian, mean, sd);
  out.sharpness = sd[0] * sd[0];
  measure_noise(grey, out);
  measure_keypoints(grey, out);
  if (!depth.empty()) measure_depth(depth, out);
  if (!previous_grey.empty() && previous_grey.size() == grey.size())
    out.motion_px = measure_motion(previous_grey, grey);
  return out;
}

Realism summarise_realism(const std::string& name, const std::vector<FrameRealism>& frames) {
  Realism r;
  r.name = name;
  r.frames = static_cast<int>(frames.size());
  std::vector<double> sharpness, keypoints, responses, motion;
  std::vector<double> noise_sum(kNoiseBins, 0.0), noise_count(kNoiseBins, 0.0);
  const size_t bins = kHoleDepthEdges.size();
  std::vector<double> holes_by_depth(bins, 0.0), pixels_by_depth(bins, 0.0);
  double pixels = 0, holes = 0, edge_pixels = 0, edge_holes = 0;
  bool depth = false;
  for (const FrameRealism& f : frames) {
    sharpness.push_back(f.sharpness);
    keypoints.push_back(f.keypoints);
    responses.push_back(f.response_median);
    for (int b = 0; b < kNoiseBins; ++b) {
      noise_sum[b] += f.noise_sum[b];
      noise_count[b] += f.noise_count[b];
    }
    if (f.has_depth) {
      depth = true;
      pixels += f.pixels, holes += f.holes;
      edge_pixels += f.edge_pixels, edge_holes += f.edge_holes;
      for (size_t b = 0; b < bins; ++b) {
        holes_by_depth[b] += f.holes_by_depth[b];
        pixels_by_depth[b] += f.pixels_by_depth[b];
      }
    }
    if (f.motion_px >= 0) motion.push_back(f.motion_px);
  }
  r.sharpness_p10 = percentile(sharpness, 0.1);
  r.sharpness_median = percentile(sharpness, 0.5);
  r.sharpness_p90 = percentile(sharpness, 0.9);
  for (int b = 0; b < kNoiseBins; ++b)
    r.noise_sigma.push_back(noise_count[b] >= kMinNoisePixels
                                ? std::sqrt(M_PI / 2.0) / 6.0 * noise_sum[b] / noise_count[b]
                                : NAN);
  r.keypoints_median = percentile(keypoints, 0.5);
  r.response_median = percentile(responses, 0.5);
  r.hole_share_by_depth.assign(bins, NAN);
  if (depth) {
    r.hole_share = holes / pixels;
    r.edge_hole_share = edge_pixels > 0 ? edge_holes / edge_pixels : NAN;
    for (size_t b = 0; b < bins; ++b)
      if (pixels_by_depth[b] > 0) r.hole_share_by_depth[b] = holes_by_depth[b] / pixels_by_depth[b];
  }
  r.motion_median = percentile(motion, 0.5);
  return r;
}

std::string format_realism_table(const Realism& s, const Realism& r) {
  const std::vector<Row> table = rows(s, r);
  size_t first = 0;
  for (const Row& row : table) first = std::max(first, row.name.size() + 2);
  const size_t column = std::max<size_t>(12, std::max(s.name.size(), r.name.size()) + 2);
  std::ostringstream o;
  o << std::left << std::setw(first) << "" << std::setw(column) << s.name << std::setw(column)
    << r.name << "ratio\n";
  for (const Row& row : table)
    o << std::setw(first) << row.name << std::setw(column) << figure(row.simulated)
      << std::setw(column) << figure(row.reference)
      << (row.name == "frames" ? "" : ratio(row.simulated, row.reference)) << "\n";
  return o.str();
}

std::string realism_page(const Realism& s, const Realism& r) {
  auto escape = [](const std::string& text) {
    std::string out;
    for (char c : text) {
      if (c == '<')
        out += "&lt;";
      else if (c == '>')
        out += "&gt;";
      else if (c == '&')
        out += "&amp;";
      else
        out += c;
    }
    return out;
  };
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Realism: " << escape(s.name)
    << " against " << escape(r.name)
    << "</title>\n<style>body{font-family:sans-serif;max-width:980px;margin:2em auto}"
       "table{border-collapse:collapse}td,th{padding:3px 10px;border-bottom:1px solid #ddd;"
       "text-align:right}td:first-child,th:first-child{text-align:left}</style></head><body>\n"
    << "<h1>Realism: " << escape(s.name) << " against " << escape(r.name) << "</h1>\n"
    << "<p>Each figure measured the same way on both recordings "
       "(<code>eval/image_realism.h</code>); a ratio near 1 means the simulation matches.</p>\n"
    << "<table><tr><th>figure</th><th>" << escape(s.name) << "</th><th>" << escape(r.name)
    << "</th><th>ratio</th></tr>\n";
  for (const Row& row : rows(s, r))
    o << "<tr><td>" << escape(row.name) << "</td><td>" << figure(row.simulated) << "</td><td>"
      << figure(row.reference) << "</td><td>"
      << (row.name == "frames" ? "" : ratio(row.simulated, row.reference)) << "</td></tr>\n";
  o << "</table>\n";
  auto plot = [&](const std::string& title, const std::string& x_label, const std::string& y_label,
                  const std::vector<std::string>& levels, const std::vector<double>& a,
                  const std::vector<double>& b) {
    SeriesPlot p;
    p.title = title;
    p.x_label = x_label;
    p.y_label = y_label;
    p.x_levels = levels;
    p.series.push_back({s.name, series_colour(0), "", a, std::vector<double>(a.size(), NAN)});
    p.series.push_back({r.name, series_colour(1), "6,3", b, std::vector<double>(b.size(), NAN)});
    try {
      o << "<h2>" << escape(title) << "</h2>\n" << render_series_plot_svg(p) << "\n";
    } catch (const Error&) {
      o << "<p>(no values to plot)</p>\n";
    }
  };
  std::vector<std::string> grey_levels;
  for (int b = 0; b < kNoiseBins; ++b)
    grey_levels.push_back(std::to_string((2 * b + 1) * 128 / kNoiseBins));
  plot("Noise by brightness", "grey level (bin centre)", "noise sigma (grey levels)", grey_levels,
       s.noise_sigma, r.noise_sigma);
  if (std::isfinite(s.hole_share) || std::isfinite(r.hole_share)) {
    std::vector<std::string> depth_levels;
    for (size_t b = 0; b < kHoleDepthEdges.size(); ++b) depth_levels.push_back(depth_bin_name(b));
    plot("Depth holes by depth", "depth of the surroundings", "share of pixels without depth",
         depth_levels, s.hole_share_by_depth, r.hole_share_by_depth);
  }
  o << "</body></html>\n";
  return o.str();
}

}  // namespace depot::eval
