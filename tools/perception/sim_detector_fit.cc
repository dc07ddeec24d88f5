#include "tools/perception/sim_detector_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <set>

#include "common/error.h"
#include "common/rng.h"
#include "slam/detect/sim_detector.h"

namespace depot::perception {
namespace {

constexpr int kRounds = 10;
constexpr double kMaxGain = 10.0;

double clamp(double v, double lo, double hi) {
  return std::min(hi, std::max(lo, v));
}

double logistic(double x) {
  return 1.0 / (1.0 + std::exp(-x));
}

double logit(double p) {
  p = clamp(p, 1e-4, 1.0 - 1e-4);
  return std::log(p / (1.0 - p));
}

double safe_log(double v) {
  return std::log(std::max(v, 1e-300));
}

// Minimises f from x0 (Nelder-Mead, standard coefficients).
std::vector<double> nelder_mead(const std::function<double(const std::vector<double>&)>& f,
                                const std::vector<double>& x0, double step, int iterations) {
  const size_t n = x0.size();
  std::vector<std::vector<double>> simplex(n + 1, x0);
  for (size_t i = 0; i < n; ++i) simplex[i + 1][i] += step;
  std::vector<double> value(n + 1);
  for (size_t i = 0; i <= n; ++i) value[i] = f(simplex[i]);
  auto point = [&](const std::vector<double>& a, const std::vector<double>& b, double t) {
    std::vector<double> p(n);
    for (size_t k = 0; k < n; ++k) p[k] = a[k] + t * (b[k] - a[k]);
    return p;
  };
  for (int it = 0; it < iterations; ++it) {
    std::vector<size_t> order(n + 1);
    for (size_t i = 0; i <= n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return value[a] < value[b]; });
    std::vector<std::vector<double>> s(n + 1);
    std::vector<double> v(n + 1);
    for (size_t i = 0; i <= n; ++i) {
      s[i] = simplex[order[i]];
      v[i] = value[order[i]];
    }
    simplex = s;
    value = v;
    if (std::abs(value[n] - value[0]) < 1e-9 * (1.0 + std::abs(value[0]))) break;
    std::vector<double> centroid(n, 0.0);
    for (size_t i = 0; i < n; ++i)
      for (size_t k = 0; k < n; ++k) centroid[k] += simplex[i][k] / static_cast<double>(n);
    const std::vector<double> reflected = point(centroid, simplex[n], -1.0);
    const double fr = f(reflected);
    if (fr < value[0]) {
      const std::vector<double> expanded = point(centroid, simplex[n], -2.0);
      const double fe = f(expanded);
      if (fe < fr) {
        simplex[n] = expanded;
        value[n] = fe;
      } else {
        simplex[n] = reflected;
        value[n] = fr;
      }
    } else if (fr < value[n - 1]) {
      simplex[n] = reflected;
      value[n] = fr;
    } else {
      const std::vector<double> contracted =
          fr < value[n] ? point(centroid, reflected, 0.5) : point(centroid, simplex[n], 0.5);
      const double fc = f(contracted);
      if (fc < std::min(fr, value[n])) {
        simplex[n] = contracted;
        value[n] = fc;
      } else {
        for (size_t i = 1; i <= n; ++i) {
          simplex[i] = point(simplex[0], simplex[i], 0.5);
          value[i] = f(simplex[i]);
        }
      }
    }
  }
  const size_t best =
      static_cast<size_t>(std::min_element(value.begin(), value.end()) - value.begin());
  return simplex[best];
}

// The probability of keeping IoU >= 0.5 against the difficulty, on a grid.
class Retention {
 public:
  Retention() : r_(kPoints, 1.0) {}
  Retention(double jitter, double scale_error, double gain) : r_(kPoints) {
    for (int i = 0; i < kPoints; ++i) {
      const double g = 1.0 + gain * i / (kPoints - 1.0);
      r_[i] = iou_retention(jitter * g, scale_error * g);
    }
  }
  double at(double d) const {
    const double x = clamp(d, 0.0, 1.0) * (kPoints - 1);
    const int i = std::min(kPoints - 2, static_cast<int>(x));
    return r_[i] + (x - i) * (r_[i + 1] - r_[i]);
  }

 private:
  static constexpr int kPoints = 21;
  std::vector<double> r_;
};

struct Shape {
  double boost = 0, occlusion = 0, small_area = 0.01;
};

// The probability that an easy box of a class is matched, given the miss
// weights u of its missed boxes and its number of matched boxes: the root
// of hits / p = sum u / (1 - p u) (the likelihood's derivative).
double fit_detection_rate(long hits, const std::vector<double>& missed_u) {
  if (hits == 0) return 0.0;
  auto slope = [&](double p) {
    double s = static_cast<double>(hits) / p;
    for (double u : missed_u) s -= u / std::max(1e-12, 1.0 - p * u);
    return s;
  };
  if (missed_u.empty() || slope(1.0 - 1e-12) >= 0) return 1.0;
  double lo = 1e-12, hi = 1.0 - 1e-12;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (lo + hi);
    (slope(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct ClassBoxes {
  std::string name;
  std::vector<const FitBox*> boxes;
  long hits = 0;
};

// u = (1 - boost s)(1 - occlusion_miss o) r(d) of a box.
double miss_weight(const FitBox& b, const Shape& shape, const Retention& retention) {
  const double s = slam::model_smallness(b.area, b.image_area, shape.small_area);
  const double d = slam::model_difficulty(s, b.occlusion);
  return (1.0 - shape.boost * s) * (1.0 - shape.occlusion * b.occlusion) * retention.at(d);
}

// The miss model's log likelihood with each class's rate profiled out;
// `rates` receives the detection rate p (1 - miss rate) per class.
double profile_log_likelihood(const std::vector<ClassBoxes>& classes, const Shape& shape,
                              const Retention& retention, std::vector<double>* rates = nullptr) {
  double ll = 0;
  std::vector<double> missed_u;
  for (size_t c = 0; c < classes.size(); ++c) {
    missed_u.clear();
    double hit_log = 0;
    for (const FitBox* b : classes[c].boxes) {
      const double u = miss_weight(*b, shape, retention);
      if (b->matched())
        hit_log += safe_log(u);
      else
        missed_u.push_back(u);
    }
    const double p = fit_detection_rate(classes[c].hits, missed_u);
    if (rates) rates->push_back(p);
    if (classes[c].hits > 0) ll += classes[c].hits * safe_log(p) + hit_log;
    for (double u : missed_u) ll += safe_log(1.0 - p * u);
  }
  return ll;
}

// From `start`, and from a few spread starts too when `spread`: the best
// wins.
Shape fit_shape(const std::vector<ClassBoxes>& classes, const Retention& retention,
                const Shape& start, bool spread) {
  auto shape_of = [](const std::vector<double>& x) {
    Shape s;
    s.boost = logistic(clamp(x[0], -12, 12));
    s.occlusion = logistic(clamp(x[1], -12, 12));
    s.small_area = logistic(clamp(x[2], -12, 12));
    return s;
  };
  auto cost = [&](const std::vector<double>& x) {
    return -profile_log_likelihood(classes, shape_of(x), retention);
  };
  std::vector<std::array<double, 3>> starts = {{start.boost, start.occlusion, start.small_area}};
  if (spread) starts.insert(starts.end(), {{0.5, 0.5, 0.05}, {0.9, 0.2, 0.3}, {0.2, 0.9, 0.01}});
  std::vector<double> best;
  double best_cost = INFINITY;
  for (const auto& s : starts) {
    std::vector<double> x = {logit(s[0]), logit(s[1]), logit(s[2])};
    for (int restart = 0; restart < 2; ++restart) x = nelder_mead(cost, x, 1.0, 400);
    const double c = cost(x);
    if (c < best_cost) {
      best_cost = c;
      best = x;
    }
  }
  return shape_of(best);
}

struct Localisation {
  double jitter = 0, scale_error = 0, gain = 0;
};

// Maximum likelihood of the sigmas and the gain over matched boxes of
// difficulty d (the gain profiled on a grid, then refined).
Localisation fit_localisation(const std::vector<const FitBox*>& matched,
                              const std::vector<double>& difficulty) {
  const double n = static_cast<double>(matched.size());
  auto sigmas = [&](double gain, double& jitter2, double& scale2, double& log_gain) {
    double j = 0, s = 0, lg = 0;
    for (size_t i = 0; i < matched.size(); ++i) {
      const FitBox& b = *matched[i];
      const double g = 1.0 + gain * difficulty[i];
      j += (b.dx * b.dx + b.dy * b.dy) / (g * g);
      s += (b.log_w * b.log_w + b.log_h * b.log_h) / (g * g);
      lg += std::log(g);
    }
    jitter2 = std::max(j / (2 * n), 1e-14);
    scale2 = std::max(s / (2 * n), 1e-14);
    log_gain = lg;
  };
  auto log_likelihood = [&](double gain) {
    double j2, s2, lg;
    sigmas(gain, j2, s2, lg);
    return -n * std::log(j2) - n * std::log(s2) - 4.0 * lg;
  };
  const int steps = 200;
  double best_gain = 0, best = log_likelihood(0);
  for (int i = 1; i <= steps; ++i) {
    const double g = kMaxGain * i / steps;
    const double v = log_likelihood(g);
    if (v > best) {
      best = v;
      best_gain = g;
    }
  }
  // Golden-section refinement around the grid's best.
  double lo = std::max(0.0, best_gain - kMaxGain / steps);
  double hi = std::min(kMaxGain, best_gain + kMaxGain / steps);
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 40; ++i) {
    const double a = hi - phi * (hi - lo), b = lo + phi * (hi - lo);
    if (log_likelihood(a) > log_likelihood(b))
      hi = b;
    else
      lo = a;
  }
  double gain = 0.5 * (lo + hi);
  if (log_likelihood(gain) < best) gain = best_gain;
  Localisation out;
  double j2, s2, lg;
  sigmas(gain, j2, s2, lg);
  out.gain = gain;
  out.jitter = std::sqrt(j2);
  out.scale_error = std::sqrt(s2);
  return out;
}

}  // namespace

double iou_retention(double jitter, double scale_error, double min_iou) {
  constexpr int kSamples = 4000;
  static const std::vector<std::array<double, 4>> normals = [] {
    Rng rng(20240601);
    std::vector<std::array<double, 4>> v(kSamples);
    for (auto& n : v) n = {rng.normal(), rng.normal(), rng.normal(), rng.normal()};
    return v;
  }();
  int kept = 0;
  for (const auto& n : normals) {
    const double cx = n[0] * jitter, cy = n[1] * jitter;
    const double w = std::exp(n[2] * scale_error), h = std::exp(n[3] * scale_error);
    const double ix = std::max(0.0, std::min(0.5, cx + 0.5 * w) - std::max(-0.5, cx - 0.5 * w));
    const double iy = std::max(0.0, std::min(0.5, cy + 0.5 * h) - std::max(-0.5, cy - 0.5 * h));
    const double inter = ix * iy;
    kept += inter / (1.0 + w * h - inter) >= min_iou;
  }
  return static_cast<double>(kept) / kSamples;
}

SimDetectorFit fit_sim_detector(const FitData& data, const slam::SimDetectorConfig& base,
                                const std::string& where) {
  SimDetectorFit fit;
  fit.boxes = static_cast<long>(data.boxes.size());
  fit.frames = data.frames;
  fit.false_positives = static_cast<long>(data.false_positive_confidences.size());
  if (data.frames <= 0) fail(where, "no frame was scored: nothing to fit the detector on");
  if (data.boxes.empty())
    fail(where, "no ground-truth box in the scored frames: nothing to fit the miss model on");

  // Per truth class, in name order.
  std::map<std::string, ClassBoxes> by_name;
  std::vector<const FitBox*> matched;
  for (const FitBox& b : data.boxes) {
    ClassBoxes& c = by_name[b.truth_class];
    c.name = b.truth_class;
    c.boxes.push_back(&b);
    ClassFit& cf = fit.classes[b.truth_class];
    ++cf.boxes;
    if (b.matched()) {
      ++c.hits;
      matched.push_back(&b);
      ++fit.matched;
      if (b.confused()) {
        ++cf.confused;
        ++fit.confused;
      } else {
        ++cf.found;
      }
    }
  }
  if (matched.empty())
    fail(where, "the detector matched none of the " + std::to_string(data.boxes.size()) +
                    " ground-truth boxes (IoU >= 0.5): nothing to fit jitter, scale_error and "
                    "the confidences on");
  long occluded = 0;
  for (const auto& [name, c] : by_name)
    if (c.hits > 0)
      for (const FitBox* b : c.boxes) occluded += b->occlusion > 0;
  if (occluded == 0)
    fail(where,
         "no partly occluded box of a class the detector matched: nothing to fit "
         "occlusion_miss on");
  std::vector<ClassBoxes> classes;
  for (auto& [name, c] : by_name) classes.push_back(std::move(c));

  // The miss model, the localisation and the IoU retention, in turn.
  Shape shape;
  shape.boost = base.small_miss_boost;
  shape.occlusion = base.occlusion_miss;
  shape.small_area = std::min(base.small_area, 0.99);
  Retention retention;
  Localisation loc;
  std::vector<double> difficulty(matched.size());
  auto difficulties = [&](const Shape& s) {
    for (size_t i = 0; i < matched.size(); ++i) {
      const FitBox& b = *matched[i];
      const double d = slam::model_difficulty(
          slam::model_smallness(b.area, b.image_area, s.small_area), b.occlusion);
      difficulty[i] = b.confused() ? std::max(d, 0.5) : d;  // as the simulator scores them
    }
  };
  for (int round = 0; round < kRounds; ++round) {
    const Shape before = shape;
    const Localisation loc_before = loc;
    shape = fit_shape(classes, retention, shape, round == 0);
    difficulties(shape);
    loc = fit_localisation(matched, difficulty);
    retention = Retention(loc.jitter, loc.scale_error, loc.gain);
    if (round > 0 && std::abs(shape.small_area - before.small_area) < 1e-4 * before.small_area &&
        std::abs(shape.boost - before.boost) < 1e-5 &&
        std::abs(shape.occlusion - before.occlusion) < 1e-5 &&
        std::abs(loc.jitter - loc_before.jitter) < 1e-6 &&
        std::abs(loc.scale_error - loc_before.scale_error) < 1e-6)
      break;
  }
  std::vector<double> rates;
  fit.miss_log_likelihood = profile_log_likelihood(classes, shape, retention, &rates);
  for (size_t c = 0; c < classes.size(); ++c)
    fit.classes[classes[c].name].miss_rate = 1.0 - rates[c];
  // Classes that were not measured: the pooled rate of all boxes.
  long hits = 0;
  std::vector<double> missed_u;
  for (const FitBox& b : data.boxes) {
    if (b.matched())
      ++hits;
    else
      missed_u.push_back(miss_weight(b, shape, retention));
  }
  const double pooled_miss = 1.0 - fit_detection_rate(hits, missed_u);

  // Confidence: least squares line c = a + b d, as max_confidence = a and
  // confidence_drop = -b / (a - min), each clamped to its range.
  const double min_c = clamp(data.min_confidence, 0.0, 1.0);
  const double n = static_cast<double>(matched.size());
  double mean_d = 0, mean_c = 0;
  for (size_t i = 0; i < matched.size(); ++i) {
    mean_d += difficulty[i] / n;
    mean_c += matched[i]->confidence / n;
  }
  double sdd = 0, sdc = 0;
  for (size_t i = 0; i < matched.size(); ++i) {
    sdd += (difficulty[i] - mean_d) * (difficulty[i] - mean_d);
    sdc += (difficulty[i] - mean_d) * (matched[i]->confidence - mean_c);
  }
  const double slope = sdd > 1e-12 ? sdc / sdd : 0.0;
  const double max_c = clamp(mean_c - slope * mean_d, min_c, 1.0);
  const double drop = max_c - min_c > 1e-9 ? clamp(-slope / (max_c - min_c), 0.0, 1.0) : 1.0;
  double rss = 0;
  for (size_t i = 0; i < matched.size(); ++i) {
    const double mean = max_c - (max_c - min_c) * drop * difficulty[i];
    rss += (matched[i]->confidence - mean) * (matched[i]->confidence - mean);
  }

  // Confusion: the observed pairs and their rate among the classes with one.
  std::map<std::string, std::set<std::string>> pairs;
  for (const FitBox* b : matched)
    if (b->confused()) pairs[b->truth_class].insert(b->detected_class);
  long with_partner = 0, confused = 0;
  for (const FitBox* b : matched)
    if (pairs.count(b->truth_class)) {
      ++with_partner;
      confused += b->confused();
    }

  // False positives: the unmatched detections, less those the simulator
  // makes itself from boxes its localisation error takes below IoU 0.5
  // (expected number and confidence under the fitted model).
  std::map<std::string, double> rate_of;
  for (size_t k = 0; k < classes.size(); ++k) rate_of[classes[k].name] = rates[k];
  double off_target = 0, off_target_confidence = 0;
  for (const FitBox& b : data.boxes) {
    const double s = slam::model_smallness(b.area, b.image_area, shape.small_area);
    const double d = slam::model_difficulty(s, b.occlusion);
    const double detected =
        rate_of[b.truth_class] * (1.0 - shape.boost * s) * (1.0 - shape.occlusion * b.occlusion);
    const double off = detected * (1.0 - retention.at(d));
    off_target += off;
    off_target_confidence += off * (max_c - (max_c - min_c) * drop * d);
  }
  double unmatched_confidence = 0;
  for (double conf : data.false_positive_confidences) unmatched_confidence += conf;
  const double fp_count = std::max(0.0, fit.false_positives - off_target);
  const double fp_rate = fp_count / data.frames;
  double fp_max = std::max(min_c, base.false_positive_max_confidence);
  if (fit.false_positives > 0) {
    // Uniform on [min, max]: max = 2 mean - min.
    const double mean = fp_count >= 1.0 ? (unmatched_confidence - off_target_confidence) / fp_count
                                        : unmatched_confidence / fit.false_positives;
    fp_max = clamp(2.0 * mean - min_c, min_c, 1.0);
  }
  fit.off_target = off_target;

  slam::SimDetectorConfig& c = fit.config;
  c = base;
  c.perfect = false;
  c.miss_rate = clamp(pooled_miss, 0.0, 1.0);
  c.class_miss_rate.clear();
  for (const auto& [name, cf] : fit.classes) c.class_miss_rate[name] = clamp(cf.miss_rate, 0, 1);
  c.small_miss_boost = shape.boost;
  c.small_area = shape.small_area;
  c.occlusion_miss = shape.occlusion;
  c.jitter = clamp(loc.jitter, 0.0, 1.0);
  c.scale_error = clamp(loc.scale_error, 0.0, 1.0);
  c.hard_jitter_gain = loc.gain;
  c.min_confidence = min_c;
  c.max_confidence = max_c;
  c.confidence_drop = drop;
  c.confidence_noise = clamp(std::sqrt(rss / matched.size()), 0.0, 1.0);
  c.false_positive_rate = clamp(fp_rate, 0.0, 10.0);
  c.false_positive_max_confidence = fp_max;
  c.class_confusion = with_partner > 0 ? static_cast<double>(confused) / with_partner : 0.0;
  c.class_confusion_rate.clear();
  c.confusions.clear();
  for (const auto& [from, to] : pairs) {
    c.confusions[from] = {to.begin(), to.end()};
    const ClassFit& cf = fit.classes[from];
    c.class_confusion_rate[from] = static_cast<double>(cf.confused) / (cf.found + cf.confused);
  }
  validate(c, where + " (fitted)");
  return fit;
}

}  // namespace depot::perception
