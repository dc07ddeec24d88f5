#pragma once
// The simulated depot at one instant: MuJoCo model and state, actors posed
// kinematically (mocap), pushables moved by physics, and the camera rig.
#include <memory>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include "common/pose.h"
#include "sim/scene/scene_model.h"

namespace depot::sim {

class World {
 public:
  explicit World(SceneModel scene);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // Steps physics to time t (s; never backwards), posing actors every step.
  void advance_to(double t);
  // Steps physics up to the last step at or before t and keeps a copy of
  // the whole state there, to come back to: a shutter whose span is longer
  // than a frame needs instants before where the world has already
  // stepped. Actors are functions of time, so the copy is all of it.
  void save_checkpoint_before(double t);
  // Back to the saved state (stepping on from it gives the same states).
  void restore_checkpoint();
  // Time of the saved state; negative when none was saved.
  double checkpoint_time() const;
  // Places the camera (T_world_camera, OpenCV axes) and updates kinematics.
  void set_camera_pose(const Pose& world_camera);

  double time() const { return data_->time; }
  double timestep() const { return model_->opt.timestep; }
  const mjModel* model() const { return model_; }
  mjData* data() { return data_; }
  int camera_id() const { return camera_id_; }
  const SceneModel& scene() const { return scene_; }
  const std::vector<Instance>& instances() const { return scene_.instances; }

  // Instance id of every geom (for the segmentation pass).
  std::vector<uint16_t> geom_instances() const;
  // Instance id of every skin (mesh-style actors; MuJoCo draws skins as
  // mjOBJ_SKIN objects, not geoms).
  std::vector<uint16_t> skin_instances() const;
  // The instance's reference pose now: actor root, pushable body, or fixed pose.
  Pose instance_pose(const Instance& instance) const;
  // Poses of every body of an instance now (articulated actors have many).
  void body_poses(const Instance& instance, std::vector<Pose>& out) const;
  // Camera pose as MuJoCo computed it (for checks).
  Pose camera_pose() const;

 private:
  void pose_actors(double t);
  // Steps physics while the next step ends before `limit` (s).
  void step_while_before(double limit);

  SceneModel scene_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  mjData* checkpoint_ = nullptr;
  int camera_id_ = -1;
  int camera_mocap_ = -1;
  std::vector<std::vector<int>> instance_bodies_;  // body ids per instance
  std::vector<std::vector<int>> actor_mocap_;      // mocap ids per actor part
  std::vector<Pose> scratch_;
  double actor_time_ = 0.0;  // time the actors were last posed at
};

// Installs MuJoCo error/warning handlers that report through depot::Error
// (once per process).
void install_mujoco_handlers();

}  // namespace depot::sim
