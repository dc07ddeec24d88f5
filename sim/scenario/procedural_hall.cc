#include "sim/scenario/procedural_hall.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/number_text.h"
#include "common/rng.h"

namespace depot::sim {
namespace {

// Sizes of what the generator places (sim/scene/depot_objects.cc builds them).
constexpr double kWallGap = 0.05;       // m, between a wall and what stands against it
constexpr double kRackDepth = 0.8;      // one rack
constexpr double kRackGap = 0.05;       // between racks in a row
constexpr double kRowDepth = 1.7;       // two racks back to back, 0.1 m apart
constexpr double kWorkArea = 3.0;       // m, along the south wall
constexpr double kSideClearance = 0.4;  // m each side of the robot in an aisle
constexpr double kSlot = 2.2;           // m, a place for goods along the south wall

double needed_width(int rows, double aisle) {
  return kWallGap + kRackDepth + rows * (aisle + kRowDepth) + aisle + kWorkArea;
}

double needed_length(double aisle, double rack_length, double cross) {
  return 2 * aisle + 2 * rack_length + cross;
}

void check_range(const HallRange& r, const char* key, double lo, double hi, bool integer) {
  const std::string name = std::string("hall.") + key;
  if (!std::isfinite(r.low) || !std::isfinite(r.high) || r.low > r.high)
    fail(r.where, name + " must be a number or a range [low, high] with low <= high");
  if (r.low < lo || r.high > hi)
    fail(r.where, fmt::format("{} = [{:g}, {:g}] is out of range [{:g}, {:g}]", name, r.low, r.high,
                              lo, hi));
  if (integer && (r.low != std::floor(r.low) || r.high != std::floor(r.high)))
    fail(r.where, name + " must be whole numbers");
}

// The racks of one row segment [x0, x1] at y, centred in it.
void place_racks(SceneLayout& layout, const std::string& prefix, double x0, double x1, double y,
                 double yaw, double rack_length, int levels) {
  const int n = static_cast<int>(std::floor((x1 - x0 + kRackGap) / (rack_length + kRackGap)));
  if (n <= 0) return;
  const double total = n * rack_length + (n - 1) * kRackGap;
  const double start = 0.5 * (x0 + x1) - 0.5 * total + 0.5 * rack_length;
  for (int i = 0; i < n; ++i) {
    SceneObject rack;
    rack.type = "rack";
    rack.name = prefix + "_" + std::to_string(layout.objects.size() + 1);
    rack.position = {start + i * (rack_length + kRackGap), y};
    rack.yaw_deg = yaw;
    rack.length = rack_length;
    rack.levels = levels;
    layout.objects.push_back(rack);
  }
}

}  // namespace

void check_procedural_hall(const ProceduralHallSpec& s) {
  check_range(s.length, "length", 8, 200, false);
  check_range(s.width, "width", 6, 200, false);
  check_range(s.height, "height", 3, 20, false);
  check_range(s.rack_rows, "rack_rows", 0, 12, true);
  check_range(s.aisle_width, "aisle_width", 0.5, 10, false);
  check_range(s.rack_length, "rack_length", 1, 5, false);
  check_range(s.rack_levels, "rack_levels", 1, 8, true);
  check_range(s.cross_aisle, "cross_aisle", 0, 20, false);
  check_range(s.clutter, "clutter", 0, 1, false);
  if (!(s.robot_width >= 0.2 && s.robot_width <= 3))
    fail(s.robot_width_where,
         "hall.robot_width = " + metres_text(s.robot_width) + " is out of range [0.2, 3] m");
  const double passage = s.robot_width + 2 * kSideClearance;
  if (s.aisle_width.low < passage)
    fail(s.aisle_width.where, "hall.aisle_width " + metres_text(s.aisle_width.low) +
                                  " is narrower than the robot and its clearance (robot_width " +
                                  metres_text(s.robot_width) +
                                  " + 2 x 0.40 m = " + metres_text(passage) + ")");
  if (s.cross_aisle.high > 0 && s.cross_aisle.low < passage)
    fail(s.cross_aisle.where, "hall.cross_aisle " + metres_text(s.cross_aisle.low) +
                                  " is narrower than the robot and its clearance (" +
                                  metres_text(passage) + "); 0 = no cross aisle");
  // The smallest hall must hold the most rows at the widest aisles.
  const int rows = static_cast<int>(s.rack_rows.high);
  const double width = needed_width(rows, s.aisle_width.high);
  if (s.width.low < width)
    fail(s.width.where,
         fmt::format("hall.width {} is too narrow for {} rack row{} with {} aisles and the {:.1f} "
                     "m work area (needs {})",
                     metres_text(s.width.low), rows, rows == 1 ? "" : "s",
                     metres_text(s.aisle_width.high), kWorkArea, metres_text(width)));
  const double length = needed_length(s.aisle_width.high, s.rack_length.high, s.cross_aisle.high);
  if (s.length.low < length)
    fail(s.length.where, "hall.length " + metres_text(s.length.low) +
                             " is too short for a rack row with its end aisles and cross aisle "
                             "(needs " +
                             metres_text(length) + ")");
}

SceneLayout generate_procedural_hall(const ProceduralHallSpec& s, uint64_t world_seed) {
  Rng rng(derive_seed(world_seed, 0x68616c6c));
  // Every parameter takes one draw, fixed or not, so fixing one leaves the
  // others' draws as they were.
  auto draw = [&](const HallRange& r) { return r.low + (r.high - r.low) * rng.uniform(); };
  auto draw_int = [&](const HallRange& r) {
    return static_cast<int>(r.low) +
           static_cast<int>(rng.below(static_cast<uint64_t>(r.high - r.low) + 1));
  };
  SceneLayout l;
  l.path = "procedural hall (world seed " + std::to_string(world_seed) + ")";
  l.length = draw(s.length);
  l.width = draw(s.width);
  l.height = draw(s.height);
  const int rows = draw_int(s.rack_rows);
  const double aisle = draw(s.aisle_width);
  const double rack_length = draw(s.rack_length);
  const int levels_north = draw_int(s.rack_levels);
  const double cross = draw(s.cross_aisle);
  const double clutter = draw(s.clutter);
  const double hx = l.length / 2, hy = l.width / 2;

  // The cross aisle's centre: near the middle, keeping a rack on each side.
  const double cross_room = std::max(0.0, hx - aisle - rack_length - cross / 2);
  const double xc = rng.uniform(-1, 1) * std::min(cross_room, l.length / 8);

  // Rack rows, north to south; aisle centres between them.
  const double y_north_row = hy - kWallGap - kRackDepth / 2;
  place_racks(l, "rack_n", -hx + 0.5, hx - 0.5, y_north_row, 0, rack_length, levels_north);
  std::vector<double> aisle_y;
  double top = hy - kWallGap - kRackDepth;  // the southern face of what stands above
  for (int k = 1; k <= rows; ++k) {
    aisle_y.push_back(top - aisle / 2);
    const double y = top - aisle - kRowDepth / 2;
    const int levels = draw_int(s.rack_levels);
    const std::string prefix = "rack_r" + std::to_string(k);
    for (double side : {1.0, -1.0}) {
      const double yy = y + side * (kRowDepth - kRackDepth) / 2;
      const double yaw = side > 0 ? 0 : 180;
      if (cross > 0) {
        place_racks(l, prefix, -hx + aisle, xc - cross / 2, yy, yaw, rack_length, levels);
        place_racks(l, prefix, xc + cross / 2, hx - aisle, yy, yaw, rack_length, levels);
      } else {
        place_racks(l, prefix, -hx + aisle, hx - aisle, yy, yaw, rack_length, levels);
      }
    }
    top = y - kRowDepth / 2;
  }
  aisle_y.push_back(top - aisle / 2);  // the south aisle, above the work area

  // The work area along the south wall: one workbench, one desk and goods in
  // places of kSlot metres, each taken with the share `clutter`; a few
  // pallets standing free in front of them.
  const int slots = std::max(0, static_cast<int>(std::floor((l.length - 1.0) / kSlot)));
  const double slot_start = -0.5 * slots * kSlot + kSlot / 2;
  std::vector<int> order(slots);
  for (int i = 0; i < slots; ++i) order[i] = i;
  for (int i = slots - 1; i > 0; --i)
    std::swap(order[i], order[rng.below(static_cast<uint64_t>(i) + 1)]);
  const double wall = -hy + kWallGap;
  int goods = 0;
  for (int n = 0; n < slots; ++n) {
    const int i = order[n];
    const double x = slot_start + i * kSlot;
    SceneObject o;
    o.position = {x, 0};
    if (n == 0) {
      o.type = "workbench", o.name = "workbench";
      o.length = 2.0, o.yaw_deg = 180, o.position.y() = wall + 0.4;
    } else if (n == 1) {
      o.type = "desk", o.name = "desk", o.yaw_deg = -90, o.length = 1.6;
      o.position.y() = wall + 0.45;
    } else {
      if (rng.uniform() >= clutter) continue;
      const double kind = rng.uniform();
      o.name = "goods_" + std::to_string(++goods);
      if (kind < 0.35) {
        o.type = "crate_stack";
        o.count = {2 + static_cast<int>(rng.below(2)), 1 + static_cast<int>(rng.below(2)),
                   1 + static_cast<int>(rng.below(3))};
        o.position.y() = wall + 0.5 * o.count.y() * 0.48 + 0.05;
      } else if (kind < 0.65) {
        o.type = "sack_pile";
        o.count = {1 + static_cast<int>(rng.below(2)), 1 + static_cast<int>(rng.below(2)),
                   1 + static_cast<int>(rng.below(3))};
        o.position.y() = wall + 0.5 * o.count.y() * 0.5 + 0.1;
      } else if (kind < 0.85) {
        o.type = "pallet";
        o.position.y() = wall + 0.45;
      } else {
        o.type = "barrel";
        o.position = {x - 0.35, wall + 0.35};
        l.objects.push_back(o);
        o.name += "b";
        o.position.x() = x + 0.35;
      }
    }
    l.objects.push_back(o);
    // A pallet standing free in the work area's open floor.
    if (n >= 2 && rng.uniform() < 0.4 * clutter) {
      SceneObject p;
      p.type = "pallet";
      p.name = "pallet_free_" + std::to_string(goods);
      p.position = {x + rng.uniform(-0.4, 0.4), wall + 2.0};
      p.yaw_deg = rng.uniform(-20, 20);
      l.objects.push_back(p);
    }
  }
  // A door in the west wall by the work area, posters on the walls.
  SceneObject door;
  door.type = "door", door.name = "door_west";
  door.position = {-hx + 0.03, -hy + kWorkArea / 2 + 0.2};
  l.objects.push_back(door);
  const int posters = 2 + static_cast<int>(rng.below(3));
  std::vector<Eigen::Vector2d> poster_at;
  for (int i = 0; i < posters; ++i) {
    SceneObject p;
    p.type = "poster", p.name = "poster_" + std::to_string(i + 1), p.z = 1.9;
    p.yaw_deg = i % 2 == 0 ? 90 : 0;  // the south wall above the goods; the east wall
    // A few tries for a place at least a poster's width (0.7 m) from the others.
    for (int attempt = 0; attempt < 20; ++attempt) {
      p.position = i % 2 == 0 ? Eigen::Vector2d(rng.uniform(-hx + 1, hx - 1), -hy + 0.02)
                              : Eigen::Vector2d(hx - 0.02, rng.uniform(-hy + 1, hy - 1));
      const bool apart = std::all_of(poster_at.begin(), poster_at.end(),
                                     [&](const auto& q) { return (q - p.position).norm() > 1.0; });
      if (apart) break;
      p.position = {NAN, NAN};
    }
    if (std::isnan(p.position.x())) continue;
    poster_at.push_back(p.position);
    l.objects.push_back(p);
  }

  // Ceiling lights: two rows of two to four, placed with jitter; one colour
  // temperature for the hall (warm to cool), each lamp a little brighter or
  // dimmer.
  const int nx = std::clamp(static_cast<int>(std::lround(l.length / 6)), 2, 4);
  const double warmth = rng.uniform();
  const Eigen::Vector3d warm(0.46, 0.41, 0.33), cool(0.38, 0.41, 0.46);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < nx; ++i) {
      SceneLight light;
      light.position = {-hx + l.length * (i + 0.5) / nx + rng.uniform(-0.4, 0.4),
                        (j == 0 ? -1 : 1) * l.width / 4 + rng.uniform(-0.4, 0.4), l.height - 0.2};
      light.colour = (warmth * warm + (1 - warmth) * cool) * rng.uniform(0.9, 1.1);
      l.lights.push_back(light);
    }
  // Paint: walls from a few real finishes, the floor lighter or darker.
  static const Eigen::Vector3d kWallPaints[] = {{1.0, 1.0, 1.0},
                                                {0.80, 0.82, 0.86},
                                                {0.74, 0.88, 0.76},
                                                {1.05, 1.0, 0.84},
                                                {0.78, 0.84, 1.0}};
  l.wall_tint = kWallPaints[rng.below(5)];
  const double floor = rng.uniform(0.8, 1.15);
  l.floor_tint = Eigen::Vector3d(floor, floor, floor * rng.uniform(0.95, 1.05));

  // Routes along the aisles.
  const double xw = -hx + aisle / 2, xe = hx - aisle / 2;
  for (size_t k = 0; k < aisle_y.size(); ++k)
    l.routes["aisle_" + std::to_string(k + 1)] = {{xw, aisle_y[k]}, {xe, aisle_y[k]}};
  for (int k = 1; k <= rows; ++k)
    l.routes["loop_row_" + std::to_string(k)] = {
        {xw, aisle_y[k]}, {xe, aisle_y[k]}, {xe, aisle_y[k - 1]}, {xw, aisle_y[k - 1]}};
  if (rows >= 1 && cross > 0) {
    l.routes["cross"] = {{xc, aisle_y.front()}, {xc, aisle_y.back()}};
    l.routes["patrol"] = {{xc, aisle_y[1]}, {xe, aisle_y[1]}, {xe, aisle_y[0]}, {xc, aisle_y[0]}};
  } else if (rows >= 1) {
    l.routes["patrol"] = l.routes["loop_row_1"];
  } else {
    l.routes["patrol"] = l.routes["aisle_1"];  // no middle row: along the north racks
  }
  return l;
}

}  // namespace depot::sim
