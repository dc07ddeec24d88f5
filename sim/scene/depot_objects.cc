#include "sim/scene/depot_objects.h"

#include <cmath>

#include "common/error.h"
#include "common/rng.h"
#include "sim/actors/limb.h"

namespace depot::sim {
namespace {

using V3 = Eigen::Vector3d;

Pose object_pose(const SceneObject& o) {
  return make_pose(rot_z(deg(o.yaw_deg)), V3(o.position.x(), o.position.y(), o.z));
}

// Goods standing on a shelf of length `length` at height z: crates, sacks
// and small barrels with gaps, filling it left to right.
void fill_shelf(std::vector<GeomDesc>& goods, Rng& rng, double length, double depth, double z,
                double max_h) {
  double x = -length / 2 + 0.05;
  while (true) {
    double kind = rng.uniform();
    double w = rng.uniform(0.3, 0.55);
    if (x + w > length / 2 - 0.05) break;
    if (rng.uniform() < 0.15) {  // a gap
      x += w;
      continue;
    }
    double h = std::min(max_h, rng.uniform(0.2, 0.42));
    double d = std::min(depth - 0.1, rng.uniform(0.3, 0.6));
    if (kind < 0.55) {
      goods.push_back(box(V3(w / 2, d / 2, h / 2),
                          V3(x + w / 2, rng.uniform(-0.05, 0.05), z + h / 2),
                          rng.uniform() < 0.5 ? "crate" : "crate_dark", rng.uniform(-0.08, 0.08)));
    } else if (kind < 0.85) {
      GeomDesc s;
      s.shape = Shape::kEllipsoid;
      s.size = V3(w / 2, d / 2, h / 2.4);
      s.local = make_pose(rot_z(rng.uniform(-0.2, 0.2)), V3(x + w / 2, 0, z + h / 2.4));
      s.material = rng.uniform() < 0.5 ? "sack" : "sack_white";
      goods.push_back(s);
    } else {
      goods.push_back(cylinder(std::min(w, d) / 2, h / 2, V3(x + w / 2, 0, z + h / 2), "barrel"));
    }
    x += w + rng.uniform(0.02, 0.1);
  }
}

std::vector<InstanceGeometry> rack(const SceneObject& o, Rng& rng) {
  const double L = o.length, D = 0.8, H = 0.55 * o.levels + 0.2;
  InstanceGeometry frame{o.name, "rack", object_pose(o), {}};
  InstanceGeometry goods{o.name + "_goods", "crate", object_pose(o), {}};
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0})
      frame.geoms.push_back(box(V3(0.04, 0.04, H / 2),
                                V3(sx * (L / 2 - 0.04), sy * (D / 2 - 0.04), H / 2), "rack_paint"));
  for (int level = 0; level < o.levels; ++level) {
    double z = 0.12 + level * 0.55;
    for (double sy : {-1.0, 1.0})
      frame.geoms.push_back(
          box(V3(L / 2 - 0.08, 0.03, 0.05), V3(0, sy * (D / 2 - 0.03), z), "rack_beam"));
    frame.geoms.push_back(box(V3(L / 2 - 0.08, D / 2 - 0.06, 0.015), V3(0, 0, z + 0.035), "shelf"));
    fill_shelf(goods.geoms, rng, L - 0.2, D, z + 0.05, 0.45);
  }
  std::vector<InstanceGeometry> out{frame};
  if (!goods.geoms.empty()) out.push_back(goods);
  return out;
}

std::vector<InstanceGeometry> crate_stack(const SceneObject& o, Rng& rng) {
  InstanceGeometry g{o.name, "crate", object_pose(o), {}};
  const V3 size(0.6, 0.45, 0.38);
  for (int k = 0; k < o.count.z(); ++k)
    for (int j = 0; j < o.count.y(); ++j)
      for (int i = 0; i < o.count.x(); ++i) {
        if (k > 0 && rng.uniform() < 0.2) continue;  // some missing on top
        V3 c((i - (o.count.x() - 1) / 2.0) * (size.x() + 0.03),
             (j - (o.count.y() - 1) / 2.0) * (size.y() + 0.03), k * size.z() + size.z() / 2);
        g.geoms.push_back(
            box(size / 2, c + V3(rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02), 0),
                rng.uniform() < 0.6 ? "crate" : "crate_dark", rng.uniform(-0.06, 0.06)));
      }
  return {g};
}

std::vector<InstanceGeometry> sack_pile(const SceneObject& o, Rng& rng) {
  InstanceGeometry g{o.name, "sack", object_pose(o), {}};
  const V3 half(0.4, 0.26, 0.11);
  for (int k = 0; k < o.count.z(); ++k)
    for (int j = 0; j < o.count.y(); ++j)
      for (int i = 0; i < o.count.x(); ++i) {
        GeomDesc s;
        s.shape = Shape::kEllipsoid;
        s.size = half;
        double shift = (k % 2) * 0.2;
        s.local = make_pose(rot_z(rng.uniform(-0.15, 0.15)),
                            V3((i - (o.count.x() - 1) / 2.0) * 0.78 + shift,
                               (j - (o.count.y() - 1) / 2.0) * 0.5, half.z() + k * 0.19));
        s.material = rng.uniform() < 0.7 ? "sack" : "sack_white";
        g.geoms.push_back(s);
      }
  return {g};
}

std::vector<InstanceGeometry> pallet(const SceneObject& o, Rng& rng) {
  InstanceGeometry g{o.name, "pallet", object_pose(o), {}};
  for (int i = 0; i < 5; ++i)
    g.geoms.push_back(box(V3(0.6, 0.06, 0.012), V3(0, -0.4 + 0.2 * i, 0.133), "pallet"));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      g.geoms.push_back(
          box(V3(0.05, 0.05, 0.06), V3(-0.55 + 0.55 * i, -0.35 + 0.35 * j, 0.06), "pallet"));
  // A load of crates on top.
  int n = 1 + static_cast<int>(rng.below(3));
  for (int k = 0; k < n; ++k)
    g.geoms.push_back(
        box(V3(0.3, 0.22, 0.19), V3(-0.28 + 0.56 * (k % 2), 0.0, 0.335 + 0.38 * (k / 2)), "crate"));
  return {g};
}

std::vector<InstanceGeometry> workbench(const SceneObject& o, Rng& rng) {
  const double L = o.length;
  InstanceGeometry g{o.name, "workbench", object_pose(o), {}};
  g.geoms.push_back(box(V3(L / 2, 0.35, 0.03), V3(0, 0, 0.9), "desk"));
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0})
      g.geoms.push_back(
          box(V3(0.03, 0.03, 0.435), V3(sx * (L / 2 - 0.05), sy * 0.3, 0.435), "bench_metal"));
  g.geoms.push_back(box(V3(L / 2, 0.02, 0.45), V3(0, 0.33, 1.38), "poster"));  // tool board
  for (int i = 0; i < 4; ++i)  // boxes and tools on the top
    g.geoms.push_back(
        box(V3(rng.uniform(0.08, 0.2), rng.uniform(0.06, 0.15), rng.uniform(0.04, 0.12)),
            V3(rng.uniform(-L / 2 + 0.3, L / 2 - 0.3), rng.uniform(-0.15, 0.15), 1.0),
            i % 2 ? "crate" : "barrel", rng.uniform(-0.5, 0.5)));
  return {g};
}

std::vector<InstanceGeometry> desk(const SceneObject& o, Rng& rng) {
  const double L = o.length;
  InstanceGeometry d{o.name, "desk", object_pose(o), {}};
  d.geoms.push_back(box(V3(kDeskDepth / 2, L / 2, 0.02), V3(0, 0, kDeskTopHeight - 0.02), "desk"));
  for (double sx : {-1.0, 1.0})
    for (double sy : {-1.0, 1.0})
      d.geoms.push_back(
          box(V3(0.025, 0.025, 0.36), V3(sx * 0.35, sy * (L / 2 - 0.05), 0.36), "dark_metal"));
  for (auto& g : d.geoms) g.replaced_by_mesh = true;  // top and legs; the papers stay
  d.geoms.push_back(
      box(V3(0.12, 0.22, 0.01), V3(-0.15, rng.uniform(-0.2, 0.2), 0.77), "poster"));  // papers
  // The monitor stands at the far (+x) edge, its screen facing -x.
  InstanceGeometry m{o.name + "_monitor", "monitor", object_pose(o), {}};
  m.geoms.push_back(box(V3(0.025, 0.27, 0.17), V3(0.25, 0, 0.98), "monitor"));
  m.geoms.push_back(box(V3(0.08, 0.1, 0.04), V3(0.27, 0, 0.8), "dark_metal"));
  return {d, m};
}

std::vector<InstanceGeometry> barrel(const SceneObject& o, Rng&) {
  InstanceGeometry g{o.name, "barrel", object_pose(o), {}};
  g.geoms.push_back(cylinder(0.29, 0.44, V3(0, 0, 0.44), "barrel"));
  return {g};
}

std::vector<InstanceGeometry> poster(const SceneObject& o, Rng&) {
  InstanceGeometry g{o.name, "structure", object_pose(o), {}};
  g.geoms.push_back(box(V3(0.01, 0.35, 0.45), V3(0, 0, 0), "poster"));
  return {g};
}

std::vector<InstanceGeometry> door(const SceneObject& o, Rng&) {
  InstanceGeometry g{o.name, "door", object_pose(o), {}};
  g.geoms.push_back(box(V3(0.03, 1.2, 1.5), V3(0, 0, 1.5), "door"));
  return {g};
}

}  // namespace

std::vector<InstanceGeometry> build_scene_object(const SceneObject& o, uint64_t seed) {
  Rng rng(derive_seed(seed, std::hash<std::string>{}(o.name) & 0xffffffffu));
  if (o.type == "rack") return rack(o, rng);
  if (o.type == "crate_stack") return crate_stack(o, rng);
  if (o.type == "sack_pile") return sack_pile(o, rng);
  if (o.type == "pallet") return pallet(o, rng);
  if (o.type == "workbench") return workbench(o, rng);
  if (o.type == "desk") return desk(o, rng);
  if (o.type == "barrel") return barrel(o, rng);
  if (o.type == "poster") return poster(o, rng);
  if (o.type == "door") return door(o, rng);
  fail(o.name, "unknown scene object type '" + o.type + "'");
}

InstanceGeometry build_pushable(const std::string& type, const std::string& name, uint64_t seed) {
  Rng rng(seed);
  InstanceGeometry g{name, type, Pose::Identity(), {}};
  auto add = [&](GeomDesc d, double friction, double density) {
    d.friction = friction;
    d.density = density;
    d.conaffinity = kCollideWorld | kCollidePusher;
    g.geoms.push_back(d);
  };
  if (type == "chair") {
    // An office chair that slides on the floor (low friction, like castors).
    add(box(V3(0.22, 0.22, 0.03), V3(0, 0, kChairSeatHeight - 0.03), "chair_fabric"), 0.1, 300);
    add(box(V3(0.03, 0.21, 0.2), V3(-0.21, 0, kChairSeatHeight + 0.26), "chair_fabric"), 0.1, 300);
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0})
        add(cylinder(0.018, (kChairSeatHeight - 0.06) / 2,
                     V3(sx * 0.19, sy * 0.19, (kChairSeatHeight - 0.06) / 2), "dark_metal"),
            0.08, 300);
    for (auto& d : g.geoms) d.replaced_by_mesh = true;  // the office chair mesh draws it all
  } else if (type == "cart") {
    add(box(V3(0.5, 0.3, 0.025), V3(0, 0, 0.22), "cart_metal"), 0.05, 250);
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0}) {
        GeomDesc wheel;
        wheel.shape = Shape::kSphere;
        wheel.size = V3(0.07, 0, 0);
        wheel.local = make_pose(Eigen::Matrix3d::Identity(), V3(sx * 0.42, sy * 0.24, 0.07));
        wheel.material = "dark_metal";
        add(wheel, 0.03, 250);
      }
    add(box(V3(0.015, 0.3, 0.33), V3(-0.5, 0, 0.57), "cart_metal"), 0.05, 250);  // handle panel
    int n = 1 + static_cast<int>(rng.below(3));
    for (int i = 0; i < n; ++i)
      add(box(V3(0.2, 0.14, 0.14), V3(-0.25 + 0.25 * i, rng.uniform(-0.1, 0.1), 0.385),
              i % 2 ? "crate_dark" : "crate"),
          0.5, 150);
  } else {
    fail(name, "not a pushable type: '" + type + "'");
  }
  return g;
}

}  // namespace depot::sim
