#include "slam/feature/orb_extractor.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "slam/feature/descriptor_distance.h"
#include "slam/feature/orb_pattern.h"

// Design notes (what follows ORB-SLAM2 and where we deliberately differ):
//  - Detection: ORB-SLAM2 runs cv::FAST (non-max suppressed) on every ~30 px cell
//    at ini_fast and again at min_fast when the cell gave nothing. We run FAST once
//    per level at ini_fast over the whole detection area and fall back to a
//    per-cell FAST at min_fast only for the cells left empty, on exactly the cell
//    window ORB-SLAM2 uses. Same keypoints (up to non-max suppression across cell
//    seams), far fewer FAST calls.
//  - Descriptors: our own steered BRIEF with the exact keypoint angle, as ORB-SLAM2.
//    cv::ORB::compute() on our keypoints would rebuild its own pyramid (double
//    work), map level coordinates by a plain division, and drop keypoints near the
//    border with runByImageBorder, so we do not use it. The test pairs are the
//    standard ones (orb_pattern.cc), so the bits are compatible with cv::ORB.
//  - Level-to-image coordinates: ORB-SLAM2 multiplies by scale^level, which is off
//    by ~0.5 (scale - 1) px at high levels. cv::resize (INTER_LINEAR) maps pixel
//    centres, and chained resizes compose exactly, so we use
//    x0 = (x + 0.5) * cols0 / cols_level - 0.5 (same for y with rows).
//  - The per-level budget follows ORB-SLAM2 (and cv::ORB): a geometric series with
//    ratio 1 / scale_factor, i.e. proportional to the level's linear size.
//  - The quadtree may end with a few more nodes than the level budget; ORB-SLAM2
//    keeps them all, we keep the best by FAST score so the total never exceeds
//    n_features.

namespace depot::slam {
namespace {

constexpr int kEdge = OrbExtractor::kEdgeThreshold;
constexpr int kRadius = OrbExtractor::kHalfPatchSize;
constexpr int kFastBorder = 3;  // cv::FAST ignores this many pixels at each side

std::string str(float v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

void validate(const OrbParams& p) {
  const char* where = "OrbExtractor";
  if (p.n_features <= 0) {
    fail(where, "n_features must be > 0, got " + std::to_string(p.n_features));
  }
  if (p.n_levels < 1 || p.n_levels > 16) {
    fail(where, "n_levels must be in [1, 16], got " + std::to_string(p.n_levels));
  }
  if (!(p.scale_factor > 1.f && p.scale_factor <= 2.f)) {  // also rejects NaN
    fail(where, "scale_factor must be in (1, 2], got " + str(p.scale_factor));
  }
  if (p.min_fast < 1 || p.min_fast > 254) {
    fail(where, "min_fast must be in [1, 254], got " + std::to_string(p.min_fast));
  }
  if (p.ini_fast < p.min_fast || p.ini_fast > 254) {
    fail(where, "ini_fast must be in [min_fast, 254] = [" + std::to_string(p.min_fast) +
                    ", 254], got " + std::to_string(p.ini_fast));
  }
}

// umax[v] = half-width of row v of a digital disc of radius r, made symmetric
// about the diagonal (umax[umax[v]] round-trips) so the patch is the same shape
// after a 90 degree rotation. Rows up to the diagonal come from the circle
// equation; the remaining rows are the transpose of those.
std::vector<int> circle_half_widths(int r) {
  const int v_max = static_cast<int>(std::floor(r * std::sqrt(2.0) / 2 + 1));
  const int v_min = static_cast<int>(std::ceil(r * std::sqrt(2.0) / 2));
  std::vector<int> lower(v_max + 1);
  for (int v = 0; v <= v_max; ++v) lower[v] = cvRound(std::sqrt(double(r * r - v * v)));
  std::vector<int> umax(r + 1);
  for (int v = 0; v < v_min; ++v) umax[v] = lower[v];
  for (int v = v_min; v <= r; ++v) {
    int u = 0;
    while (u + 1 <= v_max && lower[u + 1] >= v) ++u;  // lower[] is non-increasing
    umax[v] = u;
  }
  return umax;
}

// Orientation by intensity centroid: angle of (m10, m01) over the disc, degrees.
float centroid_angle(const cv::Mat& img, int x, int y, const std::vector<int>& umax) {
  const std::uint8_t* c = img.ptr<std::uint8_t>(y) + x;
  const std::ptrdiff_t step = static_cast<std::ptrdiff_t>(img.step1());
  int m10 = 0;
  int m01 = 0;
  for (int u = -kRadius; u <= kRadius; ++u) m10 += u * c[u];
  for (int v = 1; v <= kRadius; ++v) {
    // Rows +v and -v together: their sum feeds m10, their difference m01.
    const std::uint8_t* below = c + v * step;
    const std::uint8_t* above = c - v * step;
    int diff = 0;
    for (int u = -umax[v]; u <= umax[v]; ++u) {
      const int p = below[u];
      const int m = above[u];
      diff += p - m;
      m10 += u * (p + m);
    }
    m01 += v * diff;
  }
  return cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));
}

// Steered BRIEF: rotate every test point by the keypoint angle, round to a pixel
// and compare intensities of the smoothed image.
void steered_brief(const cv::Mat& smooth, int x, int y, float angle_deg, std::uint8_t* desc) {
  const float a = static_cast<float>(angle_deg * CV_PI / 180.0);
  const float cs = std::cos(a);
  const float sn = std::sin(a);
  const std::uint8_t* c = smooth.ptr<std::uint8_t>(y) + x;
  const int step = static_cast<int>(smooth.step1());
  const std::int8_t* pat = kOrbPattern;
  for (int byte = 0; byte < kDescriptorBytes; ++byte) {
    int val = 0;
    for (int bit = 0; bit < 8; ++bit, pat += 4) {
      const float x1 = pat[0], y1 = pat[1], x2 = pat[2], y2 = pat[3];
      const int i1 = cvRound(x1 * sn + y1 * cs) * step + cvRound(x1 * cs - y1 * sn);
      const int i2 = cvRound(x2 * sn + y2 * cs) * step + cvRound(x2 * cs - y2 * sn);
      val |= (c[i1] < c[i2]) << bit;
    }
    desc[byte] = static_cast<std::uint8_t>(val);
  }
}

// Quadtree node: half-open pixel box [x0, x1) x [y0, y1) and the range
// [begin, end) of the index array holding its keypoints.
struct Node {
  int x0, y0, x1, y1;
  int begin, end;
  int size() const { return end - begin; }
  // One keypoint, or a single pixel (cannot be split further).
  bool leaf() const { return size() <= 1 || (x1 - x0 <= 1 && y1 - y0 <= 1); }
};

// Splits n into its four quadrants (TL, TR, BL, BR) by partitioning its index
// range in place; halves round up like ORB-SLAM2's.
void split(const Node& n, const std::vector<cv::KeyPoint>& kps, std::vector<int>& idx,
           Node out[4]) {
  const int mx = n.x0 + (n.x1 - n.x0 + 1) / 2;
  const int my = n.y0 + (n.y1 - n.y0 + 1) / 2;
  const auto first = idx.begin() + n.begin;
  const auto last = idx.begin() + n.end;
  const auto mid = std::partition(first, last, [&](int i) { return kps[i].pt.y < my; });
  const auto top = std::partition(first, mid, [&](int i) { return kps[i].pt.x < mx; });
  const auto bottom = std::partition(mid, last, [&](int i) { return kps[i].pt.x < mx; });
  const int m = static_cast<int>(mid - idx.begin());
  const int t = static_cast<int>(top - idx.begin());
  const int b = static_cast<int>(bottom - idx.begin());
  out[0] = {n.x0, n.y0, mx, my, n.begin, t};
  out[1] = {mx, n.y0, n.x1, my, t, m};
  out[2] = {n.x0, my, mx, n.y1, m, b};
  out[3] = {mx, my, n.x1, n.y1, b, n.end};
}

}  // namespace

OrbExtractor::OrbExtractor(const OrbParams& params) : params_(params) {
  validate(params_);
  const int n = params_.n_levels;
  scale_.resize(n);
  inv_scale_.resize(n);
  sigma2_.resize(n);
  inv_sigma2_.resize(n);
  scale_[0] = 1.f;
  for (int l = 1; l < n; ++l) scale_[l] = scale_[l - 1] * params_.scale_factor;
  for (int l = 0; l < n; ++l) {
    inv_scale_[l] = 1.f / scale_[l];
    sigma2_[l] = scale_[l] * scale_[l];
    inv_sigma2_[l] = 1.f / sigma2_[l];
  }

  // Budget per level: n_features * (1 - q) / (1 - q^n) * q^l with q = 1 / scale,
  // rounded; the last level takes what is left so the sum is n_features.
  per_level_.assign(n, 0);
  const double q = 1.0 / params_.scale_factor;
  double desired = params_.n_features * (1.0 - q) / (1.0 - std::pow(q, n));
  int assigned = 0;
  for (int l = 0; l + 1 < n; ++l) {
    per_level_[l] = std::min(cvRound(desired), params_.n_features - assigned);
    assigned += per_level_[l];
    desired *= q;
  }
  per_level_[n - 1] = params_.n_features - assigned;

  umax_ = circle_half_widths(kRadius);
  levels_.resize(n);
  level_kps_.resize(n);
}

void OrbExtractor::build_pyramid(const cv::Mat& gray) {
  gray.copyTo(levels_[0]);
  for (int l = 1; l < params_.n_levels; ++l) {
    const cv::Size sz(cvRound(gray.cols * inv_scale_[l]), cvRound(gray.rows * inv_scale_[l]));
    if (sz.width < 1 || sz.height < 1) {
      levels_[l].release();
      continue;
    }
    // Each level from the previous one, as ORB-SLAM2 (1.2x bilinear steps alias
    // far less than one large bilinear step would).
    cv::resize(levels_[l - 1], levels_[l], sz, 0, 0, cv::INTER_LINEAR);
  }
}

void OrbExtractor::detect_level(int level, const cv::Mat& mask) {
  candidates_.clear();
  const cv::Mat& img = levels_[level];
  // Keypoint centres lie in [kEdge, cols - kEdge) x [kEdge, rows - kEdge): the
  // orientation disc (radius 15) and the rotated tests (up to 13 * sqrt(2) < 19)
  // then stay inside the level image.
  const int x_min = kEdge;
  const int y_min = kEdge;
  const int x_max = img.cols - kEdge;
  const int y_max = img.rows - kEdge;
  if (img.empty() || x_max <= x_min || y_max <= y_min) return;

  // Level-to-image mapping, for the mask (pixel centres, see design notes).
  const float sx = static_cast<float>(levels_[0].cols) / img.cols;
  const float sy = static_cast<float>(levels_[0].rows) / img.rows;
  auto allowed = [&](const cv::KeyPoint& kp) {
    if (mask.empty()) return true;
    const int u = std::clamp(cvRound((kp.pt.x + 0.5f) * sx - 0.5f), 0, mask.cols - 1);
    const int v = std::clamp(cvRound((kp.pt.y + 0.5f) * sy - 0.5f), 0, mask.rows - 1);
    return mask.at<std::uint8_t>(v, u) != 0;
  };

  // ORB-SLAM2's cell grid over [x_min - 3, x_max + 3): cells of about kCellSize
  // whose FAST windows overlap by 6 px, so the detection areas [x_min + j w,
  // x_min + (j + 1) w) tile the level without gaps.
  const int width = x_max - x_min + 2 * kFastBorder;
  const int height = y_max - y_min + 2 * kFastBorder;
  const int n_cols = std::max(1, width / kCellSize);
  const int n_rows = std::max(1, height / kCellSize);
  const int w_cell = (width + n_cols - 1) / n_cols;
  const int h_cell = (height + n_rows - 1) / n_rows;
  cell_count_.assign(static_cast<size_t>(n_cols) * n_rows, 0);

  const cv::Rect area(x_min - kFastBorder, y_min - kFastBorder, x_max - x_min + 2 * kFastBorder,
                      y_max - y_min + 2 * kFastBorder);
  cv::FAST(img(area), cell_kps_, params_.ini_fast, true);
  for (cv::KeyPoint& kp : cell_kps_) {
    kp.pt.x += static_cast<float>(area.x);
    kp.pt.y += static_cast<float>(area.y);
    if (!allowed(kp)) continue;
    const int cx = (static_cast<int>(kp.pt.x) - x_min) / w_cell;
    const int cy = (static_cast<int>(kp.pt.y) - y_min) / h_cell;
    ++cell_count_[static_cast<size_t>(cy) * n_cols + cx];
    candidates_.push_back(kp);
  }

  // Cells without a corner at ini_fast try again at min_fast.
  for (int cy = 0; cy < n_rows; ++cy) {
    const int y0 = y_min + cy * h_cell;
    const int y1 = std::min(y0 + h_cell, y_max);
    if (y0 >= y1) continue;
    for (int cx = 0; cx < n_cols; ++cx) {
      if (cell_count_[static_cast<size_t>(cy) * n_cols + cx] > 0) continue;
      const int x0 = x_min + cx * w_cell;
      const int x1 = std::min(x0 + w_cell, x_max);
      if (x0 >= x1) continue;
      const cv::Rect win(x0 - kFastBorder, y0 - kFastBorder, x1 - x0 + 2 * kFastBorder,
                         y1 - y0 + 2 * kFastBorder);
      cv::FAST(img(win), cell_kps_, params_.min_fast, true);
      for (cv::KeyPoint& kp : cell_kps_) {
        kp.pt.x += static_cast<float>(win.x);
        kp.pt.y += static_cast<float>(win.y);
        if (allowed(kp)) candidates_.push_back(kp);
      }
    }
  }
}

// ORB-SLAM2's "octree": split boxes into quadrants until there are as many
// non-empty boxes as the level budget (splitting the most crowded boxes first
// near the end), then keep the strongest corner of each box.
void OrbExtractor::distribute(int level, std::vector<cv::KeyPoint>& out) {
  out.clear();
  const int budget = per_level_[level];
  const int n_kps = static_cast<int>(candidates_.size());
  if (budget <= 0 || n_kps == 0) return;
  const cv::Mat& img = levels_[level];
  const int x_min = kEdge;
  const int y_min = kEdge;
  const int x_max = img.cols - kEdge;
  const int y_max = img.rows - kEdge;

  index_.resize(n_kps);
  for (int i = 0; i < n_kps; ++i) index_[i] = i;

  // Initial boxes: about square, side by side along the longer axis (ORB-SLAM2
  // uses columns only and crashes on portrait images; we handle both).
  const int w = x_max - x_min;
  const int h = y_max - y_min;
  const bool wide = w >= h;
  const int n_ini =
      std::max(1, static_cast<int>(std::lround(wide ? double(w) / h : double(h) / w)));
  std::vector<Node> nodes;
  nodes.reserve(static_cast<size_t>(budget) + 4);
  {
    std::vector<int> bound(n_ini + 1);
    const int len = wide ? w : h;
    const int lo = wide ? x_min : y_min;
    for (int i = 0; i <= n_ini; ++i)
      bound[i] = lo + static_cast<int>(std::lround(double(len) * i / n_ini));
    auto coord = [&](int i) { return wide ? candidates_[i].pt.x : candidates_[i].pt.y; };
    if (n_ini > 1) {
      std::sort(index_.begin(), index_.end(), [&](int a, int b) { return coord(a) < coord(b); });
    }
    int begin = 0;
    for (int i = 0; i < n_ini; ++i) {
      int end = begin;
      while (end < n_kps && (i + 1 == n_ini || coord(index_[end]) < bound[i + 1])) ++end;
      if (end > begin) {
        nodes.push_back(wide ? Node{bound[i], y_min, bound[i + 1], y_max, begin, end}
                             : Node{x_min, bound[i], x_max, bound[i + 1], begin, end});
      }
      begin = end;
    }
  }

  std::vector<Node> next;
  std::vector<int> expandable;  // indices into nodes of boxes that can be split
  Node child[4];
  bool done = false;
  while (!done) {
    const size_t prev = nodes.size();
    next.clear();
    expandable.clear();
    for (const Node& n : nodes) {
      if (n.leaf()) {
        next.push_back(n);
        continue;
      }
      split(n, candidates_, index_, child);
      for (const Node& c : child) {
        if (c.size() == 0) continue;
        if (!c.leaf()) expandable.push_back(static_cast<int>(next.size()));
        next.push_back(c);
      }
    }
    nodes.swap(next);
    if (static_cast<int>(nodes.size()) >= budget || nodes.size() == prev) break;

    // Another full round could overshoot the budget: from here on split the most
    // crowded boxes first, one at a time, until the budget is reached.
    if (static_cast<int>(nodes.size() + 3 * expandable.size()) > budget) {
      std::vector<int> next_expandable;
      while (!done) {
        const size_t before = nodes.size();
        std::stable_sort(expandable.begin(), expandable.end(),
                         [&](int a, int b) { return nodes[a].size() > nodes[b].size(); });
        next_expandable.clear();
        for (int e : expandable) {
          split(nodes[e], candidates_, index_, child);
          bool reused = false;  // the first non-empty child takes the parent's slot
          for (const Node& c : child) {
            if (c.size() == 0) continue;
            int slot;
            if (!reused) {
              slot = e;
              nodes[e] = c;
              reused = true;
            } else {
              slot = static_cast<int>(nodes.size());
              nodes.push_back(c);
            }
            if (!c.leaf()) next_expandable.push_back(slot);
          }
          if (static_cast<int>(nodes.size()) >= budget) break;
        }
        expandable.swap(next_expandable);
        done = static_cast<int>(nodes.size()) >= budget || nodes.size() == before;
      }
    }
  }

  // Strongest corner of each box; drop the weakest boxes beyond the budget.
  out.reserve(nodes.size());
  for (const Node& n : nodes) {
    int best = index_[n.begin];
    for (int k = n.begin + 1; k < n.end; ++k) {
      if (candidates_[index_[k]].response > candidates_[best].response) best = index_[k];
    }
    out.push_back(candidates_[best]);
  }
  if (static_cast<int>(out.size()) > budget) {
    std::nth_element(
        out.begin(), out.begin() + budget, out.end(),
        [](const cv::KeyPoint& a, const cv::KeyPoint& b) { return a.response > b.response; });
    out.resize(budget);
  }
}

void OrbExtractor::extract(const cv::Mat& gray, const cv::Mat& mask, std::vector<cv::KeyPoint>& kps,
                           cv::Mat& descriptors) {
  if (gray.empty()) fail("OrbExtractor::extract", "image is empty");
  if (gray.type() != CV_8UC1) {
    fail("OrbExtractor::extract",
         "image must be CV_8UC1 (8-bit grayscale), got type " + cv::typeToString(gray.type()));
  }
  if (!mask.empty() && (mask.type() != CV_8UC1 || mask.size() != gray.size())) {
    fail("OrbExtractor::extract", "mask must be empty or CV_8UC1 of the image size " +
                                      std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                                      ", got " + cv::typeToString(mask.type()) + " " +
                                      std::to_string(mask.cols) + "x" + std::to_string(mask.rows));
  }

  build_pyramid(gray);
  int total = 0;
  for (int l = 0; l < params_.n_levels; ++l) {
    detect_level(l, mask);
    distribute(l, level_kps_[l]);
    total += static_cast<int>(level_kps_[l].size());
  }

  kps.clear();
  kps.reserve(total);
  if (total == 0) {
    descriptors.release();
    return;
  }
  descriptors.create(total, kDescriptorBytes, CV_8UC1);
  int row = 0;
  for (int l = 0; l < params_.n_levels; ++l) {
    std::vector<cv::KeyPoint>& level_kps = level_kps_[l];
    if (level_kps.empty()) continue;
    const cv::Mat& img = levels_[l];
    // Descriptors on the smoothed level (7x7, sigma 2, as ORB-SLAM2 and cv::ORB);
    // orientation on the raw level.
    cv::GaussianBlur(img, blurred_, cv::Size(7, 7), 2, 2, cv::BORDER_REFLECT_101);
    const float sx = static_cast<float>(levels_[0].cols) / img.cols;
    const float sy = static_cast<float>(levels_[0].rows) / img.rows;
    const float size = kPatchSize * scale_[l];
    for (cv::KeyPoint& kp : level_kps) {
      const int x = cvRound(kp.pt.x);
      const int y = cvRound(kp.pt.y);
      kp.angle = centroid_angle(img, x, y, umax_);
      steered_brief(blurred_, x, y, kp.angle, descriptors.ptr<std::uint8_t>(row++));
      kp.octave = l;
      kp.size = size;
      kp.pt.x = (kp.pt.x + 0.5f) * sx - 0.5f;
      kp.pt.y = (kp.pt.y + 0.5f) * sy - 0.5f;
      kps.push_back(kp);
    }
  }
}

}  // namespace depot::slam
