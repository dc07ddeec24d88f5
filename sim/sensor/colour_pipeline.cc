#include "sim/sensor/colour_pipeline.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"
#include "common/rng.h"
#include "sim/sensor/auto_exposure.h"
#include "sim/sensor/kinect_model.h"
#include "sim/sensor/noise_table.h"

namespace depot::sim {

namespace {

constexpr int kLinearLevels = 65536;  // 16-bit linear raw

const std::array<float, 256>& decode_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = static_cast<float>(srgb_decode(i / 255.0));
    return t;
  }();
  return table;
}

// 16-bit linear raw -> 8-bit sRGB output.
const std::vector<uint8_t>& encode_table() {
  static const std::vector<uint8_t> table = [] {
    std::vector<uint8_t> t(kLinearLevels);
    for (int i = 0; i < kLinearLevels; ++i)
      t[i] = static_cast<uint8_t>(std::lround(255.0 * srgb_encode(i / 65535.0)));
    return t;
  }();
  return table;
}

void check_daylight(const ColourCapture& capture, const cv::Mat& bgr) {
  if (!capture.daylight.empty() &&
      (capture.daylight.type() != CV_32F || capture.daylight.size() != bgr.size()))
    fail("colour pipeline", "the daylight map differs from the image in size or type");
}

float row_level(const ColourCapture& capture, int y) {
  return capture.row_light.empty() ? 1.0f : capture.row_light[y];
}

// Linear light on the sensor (CV_32FC3, 1 = full scale): the render
// linearised, times light, exposure and vignetting, through the lens's PSF.
cv::Mat light_on_sensor(const cv::Mat& bgr, const ColourPipelineSpec& colour,
                        const ColourCapture& capture) {
  const auto& decode = decode_table();
  cv::Mat linear(bgr.size(), CV_32FC3);
  const int w = bgr.cols, h = bgr.rows;
  check_daylight(capture, bgr);
  std::vector<float> vignette(w);
  for (int y = 0; y < h; ++y) {
    const auto* in = bgr.ptr<uint8_t>(y);
    auto* out = linear.ptr<float>(y);
    const float row = static_cast<float>(capture.scale) * row_level(capture, y);
    for (int x = 0; x < w; ++x)
      vignette[x] = row * static_cast<float>(vignetting_factor(colour.vignetting, x, y, w, h));
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) out[3 * x + c] = decode[in[3 * x + c]] * vignette[x];
    if (capture.daylight.empty()) continue;
    // Daylight: its own radiance, white, through exposure and vignetting
    // but not the hall's light.
    const float* sun = capture.daylight.ptr<float>(y);
    for (int x = 0; x < w; ++x)
      if (sun[x] > 0) {
        const float v =
            sun[x] *
            static_cast<float>(capture.scale * vignetting_factor(colour.vignetting, x, y, w, h));
        out[3 * x] = out[3 * x + 1] = out[3 * x + 2] = v;
      }
  }
  if (colour.lens_blur > 0)
    cv::GaussianBlur(linear, linear, cv::Size(0, 0), colour.lens_blur, colour.lens_blur,
                     cv::BORDER_REFLECT);
  return linear;
}

// The colour channel (BGR index) of the mosaic at (x, y); `pattern` is its
// top-left 2x2 row by row, as "grbg".
int bayer_channel(const std::string& pattern, int x, int y) {
  const char c = pattern[2 * (y & 1) + (x & 1)];
  return c == 'r' ? 2 : c == 'g' ? 1 : 0;
}

// OpenCV names a Bayer pattern by the second row's second and third pixels:
// RGGB from the first row is its "BG" (the flat-colour test holds each).
int opencv_demosaic_code(const std::string& pattern, bool edge_aware) {
  if (pattern == "rggb") return edge_aware ? cv::COLOR_BayerBG2BGR_EA : cv::COLOR_BayerBG2BGR;
  if (pattern == "grbg") return edge_aware ? cv::COLOR_BayerGB2BGR_EA : cv::COLOR_BayerGB2BGR;
  if (pattern == "gbrg") return edge_aware ? cv::COLOR_BayerGR2BGR_EA : cv::COLOR_BayerGR2BGR;
  return edge_aware ? cv::COLOR_BayerRG2BGR_EA : cv::COLOR_BayerRG2BGR;  // bggr
}

// One sensor sample: shot and read noise in electrons at `gain`, the well
// and the converter saturating, to 16-bit linear.
struct Sampler {
  double electrons_per_unit = 0.0;  // full scale in electrons at this gain; 0 = no noise here
  double read_noise = 0.0;

  uint16_t operator()(float linear, int8_t unit_noise) const {
    double v = linear;
    if (electrons_per_unit > 0) {
      const double e = std::max(0.0, v) * electrons_per_unit;
      const double sigma = std::sqrt(e + read_noise * read_noise);
      v = (e + sigma * (unit_noise / 16.0)) / electrons_per_unit;
    }
    v = std::clamp(v, 0.0, 1.0);
    return static_cast<uint16_t>(std::lround(v * (kLinearLevels - 1)));
  }
};

}  // namespace

double vignetting_factor(double vignetting, double x, double y, int width, int height) {
  if (vignetting == 1.0) return 1.0;
  const double cx = 0.5 * (width - 1), cy = 0.5 * (height - 1);
  const double rho2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (cx * cx + cy * cy);
  return 1.0 - (1.0 - vignetting) * rho2;
}

void apply_colour_sensor(cv::Mat& bgr, const SensorSpec& sensor, const ColourCapture& capture,
                         uint64_t seed) {
  if (!sensor.forms_colour()) return apply_rgb_noise(bgr, sensor.rgb_noise, seed);
  const ColourPipelineSpec& colour = sensor.colour;
  const cv::Mat linear = light_on_sensor(bgr, colour, capture);
  Sampler sample;
  if (colour.full_well > 0) {
    sample.electrons_per_unit = colour.full_well / std::max(capture.gain, 1e-9);
    sample.read_noise = colour.read_noise;
  }
  Rng rng(derive_seed(seed, 0xc0105));
  const int w = bgr.cols, h = bgr.rows;
  const auto& encode = encode_table();
  if (colour.demosaic == "none") {
    for (int y = 0; y < h; ++y) {
      const float* in = linear.ptr<float>(y);
      uint8_t* out = bgr.ptr<uint8_t>(y);
      const int8_t* noise = noise_row(rng, 3 * w);
      for (int i = 0; i < 3 * w; ++i) out[i] = encode[sample(in[i], noise[i])];
    }
  } else {
    // The sensor sees one colour per pixel; the driver interpolates the
    // other two from the neighbours, on linear data, then tone-maps.
    cv::Mat raw(bgr.size(), CV_16UC1);
    for (int y = 0; y < h; ++y) {
      const float* in = linear.ptr<float>(y);
      uint16_t* out = raw.ptr<uint16_t>(y);
      const int8_t* noise = noise_row(rng, w);
      for (int x = 0; x < w; ++x)
        out[x] = sample(in[3 * x + bayer_channel(colour.bayer, x, y)], noise[x]);
    }
    cv::Mat rgb16;
    cv::cvtColor(raw, rgb16, opencv_demosaic_code(colour.bayer, colour.demosaic == "edge_aware"));
    for (int y = 0; y < h; ++y) {
      const uint16_t* in = rgb16.ptr<uint16_t>(y);
      uint8_t* out = bgr.ptr<uint8_t>(y);
      for (int i = 0; i < 3 * w; ++i) out[i] = encode[in[i]];
    }
  }
  // Without a sensor noise model the additive output noise stays as it was.
  if (colour.full_well <= 0) apply_rgb_noise(bgr, sensor.rgb_noise, seed);
  if (colour.jpeg_quality > 0) {
    std::vector<uint8_t> bytes;
    if (!cv::imencode(".jpg", bgr, bytes, {cv::IMWRITE_JPEG_QUALITY, colour.jpeg_quality}))
      fail("colour pipeline", "JPEG encoding failed");
    bgr = cv::imdecode(bytes, cv::IMREAD_COLOR);
  }
}

double metered_brightness(const cv::Mat& bgr, const ColourPipelineSpec& colour,
                          const ColourCapture& capture) {
  const auto& decode = decode_table();
  const int w = bgr.cols, h = bgr.rows;
  check_daylight(capture, bgr);
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < h; y += 4) {
    const auto* in = bgr.ptr<uint8_t>(y);
    const double row = capture.scale * row_level(capture, y);
    const float* sun = capture.daylight.empty() ? nullptr : capture.daylight.ptr<float>(y);
    for (int x = 0; x < w; x += 4) {
      const double vignette = vignetting_factor(colour.vignetting, x, y, w, h);
      ++count;
      if (sun && sun[x] > 0) {  // daylight: white at its own radiance
        sum += srgb_encode(std::min(1.0, sun[x] * capture.scale * vignette));
        continue;
      }
      const double f = row * vignette;
      auto out = [&](int c) { return srgb_encode(std::min(1.0, decode[in[3 * x + c]] * f)); };
      sum += 0.114 * out(0) + 0.587 * out(1) + 0.299 * out(2);
    }
  }
  return count ? sum / count : 0.0;
}

}  // namespace depot::sim
