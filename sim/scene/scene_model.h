#pragma once
// The compiled description of one scenario's world before MuJoCo loads it:
// MJCF text, in-memory assets, the labelled instances and the actors.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/pose.h"
#include "sim/actors/actor.h"
#include "sim/scenario/class_table.h"
#include "sim/scenario/scenario.h"
#include "sim/scenario/scene_layout.h"

namespace depot::sim {

enum class InstanceKind { kStructure, kStatic, kPushable, kActor };
const char* instance_kind_name(InstanceKind k);

// One labelled thing. Instance ids start at 1; 0 in label images means "no
// surface".
struct Instance {
  uint16_t id = 0;
  std::string name;
  std::string class_name;
  Category category = Category::kStatic;
  InstanceKind kind = InstanceKind::kStatic;
  Pose pose = Pose::Identity();     // world pose (initial, for moving ones)
  Eigen::AlignedBox3d extent;       // bounds in the instance's own frame
  std::vector<std::string> bodies;  // MuJoCo body names that belong to it
  std::vector<std::string> skins;   // MuJoCo skins drawn for it (mesh-style actors)
  std::string asset;                // catalogue entry it is drawn from; "" for primitives
  int actor = -1;                   // index into SceneModel::actors
};

struct SceneModel {
  std::string xml;
  std::vector<std::pair<std::string, std::string>> assets;  // VFS name -> bytes
  std::vector<Instance> instances;                          // instances[i].id == i + 1
  std::vector<std::unique_ptr<Actor>> actors;
  std::string camera_body = "camera_rig";
  std::string camera_name = "rgbd";
};

// Builds the depot from its layout plus the scenario's actors and pushables.
// Fails (depot::Error) on unknown classes or actors placed outside the hall.
// The camera renders `render_camera` images (the scenario's camera, or the
// wider square-pixel canvas a lens is resampled from: sim/sensor/lens.h).
SceneModel build_scene(const SceneLayout& layout, const ClassTable& classes,
                       const Scenario& scenario, const CameraIntrinsics& render_camera);

}  // namespace depot::sim
