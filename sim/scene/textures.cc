#include "sim/scene/textures.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "common/rng.h"

namespace depot::sim {
namespace {

cv::Scalar bgr(int r, int g, int b) {
  return cv::Scalar(b, g, r);
}

cv::Scalar jitter(Rng& rng, cv::Scalar c, double amount) {
  for (int i = 0; i < 3; ++i) c[i] = std::clamp(c[i] + rng.uniform(-amount, amount), 0.0, 255.0);
  return c;
}

// Adds smooth value noise: a coarse random grid upsampled with cubic
// interpolation, so it tiles nowhere but varies at the chosen scale.
void add_value_noise(cv::Mat& img, Rng& rng, int cells, double amplitude) {
  cv::Mat grid(cells, cells, CV_32F);
  for (int y = 0; y < cells; ++y)
    for (int x = 0; x < cells; ++x)
      grid.at<float>(y, x) = static_cast<float>(rng.uniform(-1.0, 1.0));
  cv::Mat up;
  cv::resize(grid, up, img.size(), 0, 0, cv::INTER_CUBIC);
  for (int y = 0; y < img.rows; ++y) {
    auto* row = img.ptr<cv::Vec3b>(y);
    const float* n = up.ptr<float>(y);
    for (int x = 0; x < img.cols; ++x)
      for (int c = 0; c < 3; ++c)
        row[x][c] = cv::saturate_cast<uchar>(row[x][c] + amplitude * n[x]);
  }
}

void add_speckles(cv::Mat& img, Rng& rng, int count, int max_radius, cv::Scalar base,
                  double spread) {
  for (int i = 0; i < count; ++i) {
    cv::Point p(static_cast<int>(rng.below(img.cols)), static_cast<int>(rng.below(img.rows)));
    int r = 1 + static_cast<int>(rng.below(max_radius));
    cv::circle(img, p, r, jitter(rng, base, spread), cv::FILLED, cv::LINE_8);
  }
}

void add_text(cv::Mat& img, Rng& rng, const std::string& text, cv::Point at, double scale,
              cv::Scalar colour, int thickness) {
  (void)rng;
  cv::putText(img, text, at, cv::FONT_HERSHEY_DUPLEX, scale, colour, thickness, cv::LINE_8);
}

std::string code(Rng& rng, const char* prefix) {
  return prefix + std::to_string(100 + rng.below(900));
}

cv::Mat filled(int size, cv::Scalar c) {
  return cv::Mat(size, size, CV_8UC3, c);
}

// --- the depot ------------------------------------------------------------

cv::Mat concrete(Rng& rng, int n) {
  cv::Mat img = filled(n, bgr(148, 146, 140));
  add_value_noise(img, rng, 8, 14);
  add_value_noise(img, rng, 40, 8);
  add_speckles(img, rng, n * 3, 3, bgr(90, 90, 88), 25);
  add_speckles(img, rng, n, 2, bgr(200, 198, 192), 20);
  for (int i = 0; i < 6; ++i) {  // cracks
    cv::Point p(static_cast<int>(rng.below(n)), static_cast<int>(rng.below(n)));
    for (int k = 0; k < 8; ++k) {
      cv::Point q = p + cv::Point(static_cast<int>(rng.uniform(-30, 30)),
                                  static_cast<int>(rng.uniform(-30, 30)));
      cv::line(img, p, q, bgr(70, 70, 68), 1, cv::LINE_8);
      p = q;
    }
  }
  for (int i = 0; i < 5; ++i)  // oil stains
    cv::ellipse(img, cv::Point(static_cast<int>(rng.below(n)), static_cast<int>(rng.below(n))),
                cv::Size(10 + static_cast<int>(rng.below(30)), 6 + static_cast<int>(rng.below(20))),
                rng.uniform(0, 180), 0, 360, bgr(105, 100, 95), cv::FILLED);
  return img;
}

cv::Mat brick(Rng& rng, int n) {
  cv::Mat img = filled(n, bgr(190, 185, 175));  // mortar
  const int rows = 16, cols = 8;
  const int bh = n / rows, bw = n / cols;
  for (int r = 0; r < rows; ++r) {
    int shift = (r % 2) * bw / 2;
    for (int c = -1; c < cols; ++c) {
      cv::Rect rect(c * bw + shift + 2, r * bh + 2, bw - 4, bh - 4);
      cv::rectangle(img, rect, jitter(rng, bgr(160, 70, 50), 35), cv::FILLED);
    }
  }
  add_value_noise(img, rng, 32, 10);
  add_speckles(img, rng, n, 2, bgr(80, 40, 30), 20);
  return img;
}

cv::Mat ceiling(Rng& rng, int n) {
  cv::Mat img = filled(n, bgr(215, 215, 210));
  for (int i = 0; i <= 4; ++i) {
    cv::line(img, cv::Point(i * n / 4, 0), cv::Point(i * n / 4, n), bgr(120, 120, 120), 3);
    cv::line(img, cv::Point(0, i * n / 4), cv::Point(n, i * n / 4), bgr(120, 120, 120), 3);
  }
  add_value_noise(img, rng, 16, 8);
  return img;
}

cv::Mat wood(Rng& rng, int n, cv::Scalar base, bool stencil) {
  cv::Mat img = filled(n, base);
  const int planks = 5;
  for (int p = 0; p < planks; ++p) {
    cv::Rect rect(0, p * n / planks, n, n / planks);
    img(rect).setTo(jitter(rng, base, 25));
    for (int g = 0; g < 12; ++g) {  // grain
      int y = rect.y + static_cast<int>(rng.below(rect.height));
      cv::line(img, cv::Point(0, y), cv::Point(n, y + static_cast<int>(rng.uniform(-6, 6))),
               jitter(rng, base * 0.7, 10), 1);
    }
    cv::line(img, cv::Point(0, rect.y), cv::Point(n, rect.y), base * 0.4, 2);
    for (int k = 0; k < 2; ++k)  // nails
      cv::circle(img, cv::Point(static_cast<int>(n * (0.08 + 0.84 * k)), rect.y + rect.height / 2),
                 3, bgr(50, 50, 55), cv::FILLED);
  }
  cv::rectangle(img, cv::Rect(0, 0, n, n), base * 0.45, std::max(3, n / 40));
  if (stencil) {
    add_text(img, rng, code(rng, "LOT "), cv::Point(n / 8, n / 2), n / 200.0, bgr(25, 25, 30), 2);
    add_text(img, rng, "FRAGILE", cv::Point(n / 8, n * 3 / 4), n / 260.0, bgr(150, 20, 20), 2);
  }
  add_value_noise(img, rng, 24, 10);
  return img;
}

cv::Mat burlap(Rng& rng, int n, cv::Scalar base) {
  cv::Mat img = filled(n, base);
  for (int i = 0; i < n; i += 4) {
    cv::line(img, cv::Point(i, 0), cv::Point(i, n), base * 0.8, 1);
    cv::line(img, cv::Point(0, i), cv::Point(n, i), base * 0.85, 1);
  }
  add_value_noise(img, rng, 12, 18);
  cv::rectangle(img, cv::Rect(n / 5, n / 4, n * 3 / 5, n / 2), bgr(30, 90, 40), 3);
  add_text(img, rng, "FEED", cv::Point(n / 4, n / 2), n / 150.0, bgr(30, 90, 40), 2);
  add_text(img, rng, code(rng, "25KG "), cv::Point(n / 4, n * 2 / 3), n / 280.0, bgr(40, 40, 40),
           1);
  return img;
}

cv::Mat painted_metal(Rng& rng, int n, cv::Scalar base) {
  cv::Mat img = filled(n, base);
  add_value_noise(img, rng, 16, 12);
  add_speckles(img, rng, n / 2, 2, bgr(60, 60, 60), 30);  // chipped paint
  for (int i = 0; i < 10; ++i) {                          // punched holes of a rack upright
    int y = (i * n) / 10 + n / 20;
    cv::rectangle(img, cv::Rect(n / 2 - 5, y, 10, 14), bgr(30, 30, 30), cv::FILLED);
  }
  cv::rectangle(img, cv::Rect(n / 10, n / 10, n / 3, n / 6), bgr(240, 240, 235),
                cv::FILLED);  // label
  add_text(img, rng, code(rng, "A-"), cv::Point(n / 10 + 4, n / 10 + n / 8), n / 400.0,
           bgr(10, 10, 10), 1);
  return img;
}

cv::Mat monitor(Rng& rng, int n) {
  cv::Mat img = filled(n, bgr(25, 25, 28));
  cv::Rect screen(n / 12, n / 12, n * 10 / 12, n * 10 / 12);
  img(screen).setTo(bgr(30, 60, 110));
  for (int w = 0; w < 4; ++w) {  // windows
    cv::Rect r(screen.x + static_cast<int>(rng.below(screen.width / 2)),
               screen.y + static_cast<int>(rng.below(screen.height / 2)), screen.width / 3,
               screen.height / 3);
    cv::rectangle(img, r, bgr(230, 230, 225), cv::FILLED);
    cv::rectangle(img, cv::Rect(r.x, r.y, r.width, 10), bgr(60, 90, 160), cv::FILLED);
    for (int l = 0; l < 5; ++l)
      cv::line(img, cv::Point(r.x + 6, r.y + 20 + l * 10),
               cv::Point(r.x + 6 + static_cast<int>(rng.below(r.width - 12)), r.y + 20 + l * 10),
               bgr(40, 40, 40), 2);
  }
  return img;
}

cv::Mat poster(Rng& rng, int n) {
  cv::Mat img = filled(n, bgr(240, 238, 225));
  cv::rectangle(img, cv::Rect(0, 0, n, n / 5), jitter(rng, bgr(200, 40, 30), 40), cv::FILLED);
  add_text(img, rng, "SAFETY", cv::Point(n / 10, n / 7), n / 180.0, bgr(255, 255, 255), 2);
  for (int i = 0; i < 6; ++i) {
    int y = n / 4 + i * n / 9;
    cv::circle(img, cv::Point(n / 8, y), n / 30, jitter(rng, bgr(40, 120, 40), 60), cv::FILLED);
    add_text(img, rng, code(rng, "RULE "), cv::Point(n / 5, y + 5), n / 420.0, bgr(20, 20, 20), 1);
  }
  return img;
}

cv::Mat door(Rng& rng, int n) {
  cv::Mat img = filled(n, bgr(70, 95, 80));
  for (int i = 1; i < 8; ++i)
    cv::line(img, cv::Point(0, i * n / 8), cv::Point(n, i * n / 8), bgr(50, 70, 60), 3);
  cv::rectangle(img, cv::Rect(n / 3, n / 12, n / 3, n / 8), bgr(240, 200, 30), cv::FILLED);
  add_text(img, rng, "EXIT", cv::Point(n / 3 + 8, n / 12 + n / 10), n / 300.0, bgr(10, 10, 10), 2);
  add_value_noise(img, rng, 16, 10);
  return img;
}

// --- actors ---------------------------------------------------------------

cv::Mat shirt(Rng& rng, int n, int style) {
  static const cv::Scalar kColours[] = {bgr(200, 40, 40),  bgr(40, 80, 180),  bgr(40, 140, 60),
                                        bgr(230, 200, 40), bgr(240, 120, 20), bgr(90, 90, 95)};
  cv::Scalar base = kColours[style % 6];
  cv::Mat img = filled(n, base);
  switch (style % 6) {
    case 0:  // plaid
      for (int i = 0; i < n; i += n / 8) {
        cv::rectangle(img, cv::Rect(i, 0, n / 24, n), bgr(30, 30, 30), cv::FILLED);
        cv::rectangle(img, cv::Rect(0, i, n, n / 24), bgr(240, 240, 240), cv::FILLED);
      }
      break;
    case 1:  // stripes
      for (int i = 0; i < n; i += n / 10)
        cv::rectangle(img, cv::Rect(0, i, n, n / 20), bgr(245, 245, 245), cv::FILLED);
      break;
    case 2:  // logo shirt
      cv::circle(img, cv::Point(n / 2, n / 2), n / 5, bgr(250, 250, 250), cv::FILLED);
      add_text(img, rng, "FARM", cv::Point(n / 3, n / 2 + 8), n / 280.0, bgr(20, 20, 20), 2);
      break;
    case 3:  // hi-vis vest
    case 4:
      cv::rectangle(img, cv::Rect(0, n / 3, n, n / 12), bgr(210, 210, 210), cv::FILLED);
      cv::rectangle(img, cv::Rect(0, 2 * n / 3, n, n / 12), bgr(210, 210, 210), cv::FILLED);
      add_text(img, rng, "DEPOT", cv::Point(n / 6, n / 5), n / 250.0, bgr(20, 20, 20), 2);
      break;
    default:  // checks
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          if ((x + y) % 2)
            cv::rectangle(img, cv::Rect(x * n / 8, y * n / 8, n / 8, n / 8), bgr(160, 160, 170),
                          cv::FILLED);
  }
  add_value_noise(img, rng, 20, 12);
  add_speckles(img, rng, n / 4, 2, base * 0.5, 20);
  return img;
}

cv::Mat denim(Rng& rng, int n, cv::Scalar base) {
  cv::Mat img = filled(n, base);
  for (int i = -n; i < n; i += 3)
    cv::line(img, cv::Point(i, 0), cv::Point(i + n, n), base * 0.8, 1);
  add_value_noise(img, rng, 10, 18);
  cv::rectangle(img, cv::Rect(n / 4, n / 5, n / 5, n / 6), base * 0.6, 2);  // pocket
  add_speckles(img, rng, n / 3, 2, base * 1.3, 15);
  return img;
}

cv::Mat skin(Rng& rng, int n, cv::Scalar base) {
  cv::Mat img = filled(n, base);
  add_value_noise(img, rng, 6, 10);
  // Eyes and mouth give the head some structure whatever the mapping.
  for (int k = 0; k < 2; ++k)
    cv::circle(img, cv::Point(n / 3 + k * n / 3, n / 2 - n / 10), n / 18, bgr(30, 25, 25),
               cv::FILLED);
  cv::line(img, cv::Point(n / 3, n * 2 / 3), cv::Point(n * 2 / 3, n * 2 / 3), bgr(120, 50, 50), 3);
  return img;
}

cv::Mat fur(Rng& rng, int n, cv::Scalar base, cv::Scalar patch, bool stripes) {
  cv::Mat img = filled(n, base);
  add_value_noise(img, rng, 10, 25);
  if (stripes) {
    for (int i = 0; i < n; i += n / 9)
      cv::line(img, cv::Point(0, i), cv::Point(n, i + n / 12), patch, n / 40);
  } else {
    for (int i = 0; i < 7; ++i)
      cv::ellipse(img, cv::Point(static_cast<int>(rng.below(n)), static_cast<int>(rng.below(n))),
                  cv::Size(n / 10 + static_cast<int>(rng.below(n / 8)),
                           n / 12 + static_cast<int>(rng.below(n / 10))),
                  rng.uniform(0, 180), 0, 360, patch, cv::FILLED);
  }
  for (int i = 0; i < n * 2; ++i) {  // hair strokes
    cv::Point p(static_cast<int>(rng.below(n)), static_cast<int>(rng.below(n)));
    cv::line(img, p, p + cv::Point(static_cast<int>(rng.uniform(-4, 4)), 5),
             jitter(rng, base * 0.6, 20), 1);
  }
  return img;
}

cv::Mat mesh_metal(Rng& rng, int n) {
  cv::Mat img = filled(n, bgr(170, 172, 175));
  for (int i = 0; i < n; i += n / 12) {
    cv::line(img, cv::Point(i, 0), cv::Point(i, n), bgr(80, 80, 85), 2);
    cv::line(img, cv::Point(0, i), cv::Point(n, i), bgr(80, 80, 85), 2);
  }
  add_value_noise(img, rng, 12, 10);
  return img;
}

}  // namespace

TextureSet make_depot_textures(uint64_t seed, int cube, int plane) {
  TextureSet set;
  Rng rng(derive_seed(seed, 0x7e47));
  auto tex = [&](const std::string& name, cv::Mat img, bool is_cube) {
    set.textures.push_back({name, img, is_cube});
  };
  auto mat = [&](const std::string& name, const std::string& texture, double repeat = 1.0) {
    MaterialSpec m;
    m.name = name;
    m.texture = texture;
    m.texrepeat = repeat;
    set.materials.push_back(m);
  };
  // Planes: one texture tile spans 2 m (repeat 0.5 per metre).
  tex("concrete", concrete(rng, plane), false), mat("floor", "concrete", 0.5);
  tex("brick", brick(rng, plane), false), mat("wall", "brick", 0.5);
  tex("ceiling", ceiling(rng, plane), false), mat("ceiling", "ceiling", 0.5);
  // Objects (cube maps).
  tex("crate_wood", wood(rng, cube, bgr(185, 140, 90), true), true), mat("crate", "crate_wood");
  tex("crate_dark", wood(rng, cube, bgr(130, 95, 60), true), true), mat("crate_dark", "crate_dark");
  tex("pallet_wood", wood(rng, cube, bgr(200, 170, 120), false), true),
      mat("pallet", "pallet_wood");
  tex("shelf_wood", wood(rng, cube, bgr(170, 150, 110), false), true), mat("shelf", "shelf_wood");
  tex("desk_top", wood(rng, cube, bgr(150, 110, 80), false), true), mat("desk", "desk_top");
  tex("burlap", burlap(rng, cube, bgr(190, 165, 120)), true), mat("sack", "burlap");
  tex("burlap_white", burlap(rng, cube, bgr(225, 220, 205)), true),
      mat("sack_white", "burlap_white");
  tex("rack_orange", painted_metal(rng, cube, bgr(230, 110, 30)), true),
      mat("rack_paint", "rack_orange");
  tex("rack_blue", painted_metal(rng, cube, bgr(40, 70, 150)), true), mat("rack_beam", "rack_blue");
  tex("barrel_blue", painted_metal(rng, cube, bgr(30, 60, 170)), true),
      mat("barrel", "barrel_blue");
  tex("bench_green", painted_metal(rng, cube, bgr(60, 110, 70)), true),
      mat("bench_metal", "bench_green");
  tex("monitor", monitor(rng, cube), true), mat("monitor", "monitor");
  tex("poster", poster(rng, cube), true), mat("poster", "poster");
  tex("door", door(rng, cube), true), mat("door", "door");
  tex("mesh_metal", mesh_metal(rng, cube), true), mat("cart_metal", "mesh_metal");
  tex("chair_fabric", denim(rng, cube, bgr(60, 60, 70)), true), mat("chair_fabric", "chair_fabric");
  // Actors.
  for (int i = 0; i < 6; ++i) {
    std::string n = "shirt_" + std::to_string(i);
    tex(n, shirt(rng, cube, i), true), mat(n, n);
  }
  const cv::Scalar pants[] = {bgr(50, 70, 120), bgr(160, 140, 100), bgr(40, 40, 45)};
  for (int i = 0; i < 3; ++i) {
    std::string n = "pants_" + std::to_string(i);
    tex(n, denim(rng, cube, pants[i]), true), mat(n, n);
  }
  const cv::Scalar skins[] = {bgr(235, 195, 165), bgr(190, 140, 100), bgr(120, 80, 55)};
  for (int i = 0; i < 3; ++i) {
    std::string n = "skin_" + std::to_string(i);
    tex(n, skin(rng, cube, skins[i]), true), mat(n, n);
  }
  tex("hair_0", fur(rng, cube, bgr(40, 30, 25), bgr(20, 15, 12), true), true),
      mat("hair_0", "hair_0");
  tex("hair_1", fur(rng, cube, bgr(120, 80, 40), bgr(90, 60, 30), true), true),
      mat("hair_1", "hair_1");
  tex("shoes", fur(rng, cube, bgr(35, 30, 30), bgr(70, 60, 50), false), true),
      mat("shoes", "shoes");
  tex("fur_dog_0", fur(rng, cube, bgr(150, 100, 50), bgr(240, 235, 225), false), true),
      mat("fur_dog_0", "fur_dog_0");
  tex("fur_dog_1", fur(rng, cube, bgr(30, 28, 25), bgr(190, 140, 80), false), true),
      mat("fur_dog_1", "fur_dog_1");
  tex("fur_cat_0", fur(rng, cube, bgr(200, 130, 60), bgr(120, 70, 30), true), true),
      mat("fur_cat_0", "fur_cat_0");
  tex("fur_cat_1", fur(rng, cube, bgr(130, 130, 135), bgr(60, 60, 65), true), true),
      mat("fur_cat_1", "fur_cat_1");
  tex("pig_skin", fur(rng, cube, bgr(240, 175, 170), bgr(180, 110, 110), false), true),
      mat("pig_skin", "pig_skin");
  tex("feathers_0", fur(rng, cube, bgr(120, 110, 100), bgr(40, 35, 30), true), true),
      mat("feathers_0", "feathers_0");
  tex("feathers_1", fur(rng, cube, bgr(220, 220, 215), bgr(60, 60, 60), true), true),
      mat("feathers_1", "feathers_1");
  mat("snout", "");
  set.materials.back().rgba[0] = 0.25, set.materials.back().rgba[1] = 0.18,
  set.materials.back().rgba[2] = 0.16;
  mat("beak", "");
  set.materials.back().rgba[0] = 0.95, set.materials.back().rgba[1] = 0.6,
  set.materials.back().rgba[2] = 0.1;
  mat("dark_metal", "");
  set.materials.back().rgba[0] = 0.2, set.materials.back().rgba[1] = 0.2,
  set.materials.back().rgba[2] = 0.22;
  return set;
}

}  // namespace depot::sim
