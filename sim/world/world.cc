#include "sim/world/world.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>

#include "common/error.h"
#include "common/staged_directory.h"

namespace depot::sim {
namespace {

Pose body_pose(const mjModel* m, const mjData* d, int body) {
  (void)m;
  Eigen::Matrix3d r;
  for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = d->xmat[9 * body + i];
  return make_pose(
      r, Eigen::Vector3d(d->xpos[3 * body], d->xpos[3 * body + 1], d->xpos[3 * body + 2]));
}

void set_mocap(mjData* d, int mocap, const Pose& p) {
  Eigen::Quaterniond q(p.linear());
  q.normalize();
  for (int i = 0; i < 3; ++i) d->mocap_pos[3 * mocap + i] = p.translation()[i];
  d->mocap_quat[4 * mocap + 0] = q.w();
  d->mocap_quat[4 * mocap + 1] = q.x();
  d->mocap_quat[4 * mocap + 2] = q.y();
  d->mocap_quat[4 * mocap + 3] = q.z();
}

// MuJoCo's default error handler exits; ours reports one line and removes
// any half-written output first (unwinding through C code is not possible).
void mujoco_error(const char* msg) {
  std::fprintf(stderr, "depot: error: MuJoCo: %s\n", msg);
  remove_all_staged_directories();
  std::_Exit(1);
}

void mujoco_warning(const char* msg) {
  std::fprintf(stderr, "depot: warning: MuJoCo: %s\n", msg);
}

}  // namespace

void install_mujoco_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = mujoco_error;
    mju_user_warning = mujoco_warning;
  });
}

World::World(SceneModel scene) : scene_(std::move(scene)) {
  install_mujoco_handlers();
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  auto add_file = [&](const std::string& name, const std::string& bytes) {
    if (mj_makeEmptyFileVFS(vfs.get(), name.c_str(), static_cast<int>(bytes.size())) != 0)
      fail("scene", "cannot add '" + name + "' to the MuJoCo VFS");
    int i = mj_findFileVFS(vfs.get(), name.c_str());
    std::memcpy(vfs->filedata[i], bytes.data(), bytes.size());
  };
  for (const auto& [name, bytes] : scene_.assets) add_file(name, bytes);
  add_file("depot.xml", scene_.xml);
  char error[1000] = "";
  model_ = mj_loadXML("depot.xml", vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (!model_) fail("scene", std::string("MuJoCo rejected the generated model: ") + error);
  data_ = mj_makeData(model_);

  camera_id_ = mj_name2id(model_, mjOBJ_CAMERA, scene_.camera_name.c_str());
  int camera_body = mj_name2id(model_, mjOBJ_BODY, scene_.camera_body.c_str());
  if (camera_id_ < 0 || camera_body < 0) fail("scene", "camera rig missing");
  camera_mocap_ = model_->body_mocapid[camera_body];

  instance_bodies_.resize(scene_.instances.size());
  actor_mocap_.resize(scene_.actors.size());
  for (size_t i = 0; i < scene_.instances.size(); ++i) {
    const Instance& inst = scene_.instances[i];
    for (const auto& name : inst.bodies) {
      int b = name == "world" ? 0 : mj_name2id(model_, mjOBJ_BODY, name.c_str());
      if (b < 0) fail("scene", "body '" + name + "' missing from compiled model");
      instance_bodies_[i].push_back(b);
      if (inst.actor >= 0 && model_->body_mocapid[b] >= 0)
        actor_mocap_[inst.actor].push_back(model_->body_mocapid[b]);
    }
  }
  // Let pushables settle on the floor before time starts, so contact
  // settling is not mistaken for motion in the first frames.
  pose_actors(0.0);
  for (int i = 0; i < 250; ++i) mj_step(model_, data_);
  mju_zero(data_->qvel, model_->nv);
  data_->time = 0.0;
  mj_forward(model_, data_);
}

World::~World() {
  if (checkpoint_) mj_deleteData(checkpoint_);
  if (data_) mj_deleteData(data_);
  if (model_) mj_deleteModel(model_);
}

std::vector<uint16_t> World::geom_instances() const {
  std::vector<int> body_instance(model_->nbody, 0);
  for (size_t i = 0; i < instance_bodies_.size(); ++i)
    for (int b : instance_bodies_[i]) body_instance[b] = scene_.instances[i].id;
  std::vector<uint16_t> out(model_->ngeom, 0);
  for (int g = 0; g < model_->ngeom; ++g)
    out[g] = static_cast<uint16_t>(body_instance[model_->geom_bodyid[g]]);
  return out;
}

std::vector<uint16_t> World::skin_instances() const {
  std::vector<uint16_t> out(model_->nskin, 0);
  for (const Instance& inst : scene_.instances)
    for (const auto& name : inst.skins) {
      const int s = mj_name2id(model_, mjOBJ_SKIN, name.c_str());
      if (s < 0) fail("scene", "skin '" + name + "' missing from compiled model");
      out[s] = inst.id;
    }
  return out;
}

void World::pose_actors(double t) {
  actor_time_ = t;
  for (size_t a = 0; a < scene_.actors.size(); ++a) {
    scene_.actors[a]->pose_parts(t, scratch_);
    for (size_t p = 0; p < scratch_.size(); ++p) set_mocap(data_, actor_mocap_[a][p], scratch_[p]);
    // A skinned actor's bone bodies follow its parts' (scene_builder order).
    const size_t first_bone = scratch_.size();
    scene_.actors[a]->pose_bones(t, scratch_);
    for (size_t b = 0; b < scratch_.size(); ++b)
      set_mocap(data_, actor_mocap_[a][first_bone + b], scratch_[b]);
  }
}

void World::step_while_before(double limit) {
  const double dt = model_->opt.timestep;
  while (data_->time + dt < limit) {
    pose_actors(data_->time + dt);
    mj_step(model_, data_);
  }
}

void World::advance_to(double t) {
  // To the physics step nearest t.
  step_while_before(t + 0.5 * model_->opt.timestep);
  pose_actors(t);
  mj_forward(model_, data_);
}

void World::save_checkpoint_before(double t) {
  step_while_before(t + 1e-12);
  if (!checkpoint_) checkpoint_ = mj_makeData(model_);
  mj_copyData(checkpoint_, model_, data_);
}

void World::restore_checkpoint() {
  if (!checkpoint_) fail("world", "no checkpoint to restore");
  mj_copyData(data_, model_, checkpoint_);
}

double World::checkpoint_time() const {
  return checkpoint_ ? checkpoint_->time : -1.0;
}

void World::set_camera_pose(const Pose& world_camera) {
  // MuJoCo cameras look along -z with y up: flip the OpenCV y and z axes.
  Pose rig = world_camera;
  rig.linear() = world_camera.linear() * Eigen::Vector3d(1, -1, -1).asDiagonal();
  set_mocap(data_, camera_mocap_, rig);
  mj_kinematics(model_, data_);
  mj_camlight(model_, data_);
}

Pose World::camera_pose() const {
  Eigen::Matrix3d r;
  for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = data_->cam_xmat[9 * camera_id_ + i];
  Eigen::Vector3d t(data_->cam_xpos[3 * camera_id_], data_->cam_xpos[3 * camera_id_ + 1],
                    data_->cam_xpos[3 * camera_id_ + 2]);
  return make_pose(Eigen::Matrix3d(r * Eigen::Vector3d(1, -1, -1).asDiagonal()), t);
}

Pose World::instance_pose(const Instance& inst) const {
  switch (inst.kind) {
    case InstanceKind::kActor:
      return scene_.actors[inst.actor]->root_pose(actor_time_);
    case InstanceKind::kPushable:
      return body_pose(model_, data_, instance_bodies_[inst.id - 1][0]);
    default:
      return inst.pose;
  }
}

void World::body_poses(const Instance& inst, std::vector<Pose>& out) const {
  out.clear();
  for (int b : instance_bodies_[inst.id - 1]) out.push_back(body_pose(model_, data_, b));
}

}  // namespace depot::sim
