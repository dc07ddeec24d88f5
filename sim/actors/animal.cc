#include "sim/actors/animal.h"

#include <algorithm>
#include <cmath>

#include "common/rng.h"
#include "sim/actors/limb.h"

namespace depot::sim {

// ---------------------------------------------------------------- quadruped

QuadrupedActor::QuadrupedActor(const ActorSpec& spec) {
  name_ = spec.name;
  class_name_ = spec.type;
  Rng rng(spec.appearance);
  scale_ = spec.size * rng.uniform(0.9, 1.1);
  mesh_scale_ = spec.size;
  speed_ = spec.speed;
  offset_ = spec.start_offset;
  start_time_ = spec.start_time;
  gait_phase_ = spec.gait_phase;
  path_ = actor_path(spec);
  std::string fur;
  if (spec.type == "dog") {
    b_ = {0.24, 0.13, 0.50, 0.38, 0.045, 0.11, 0.9, 0.25};
    fur = "fur_dog_" + std::to_string(rng.below(2));
  } else if (spec.type == "cat") {
    b_ = {0.16, 0.075, 0.27, 0.21, 0.025, 0.065, 0.5, 0.25};
    fur = "fur_cat_" + std::to_string(rng.below(2));
  } else {  // pig
    b_ = {0.40, 0.24, 0.50, 0.26, 0.06, 0.17, 0.7, 0.10};
    fur = "pig_skin";
  }
  // Legs hang from the body axis down to the floor.
  b_.leg_length = b_.body_height - b_.leg_radius;
  const double s = scale_;
  parts_.push_back({"body", spec.type == "pig" ? Shape::kEllipsoid : Shape::kCapsule,
                    spec.type == "pig"
                        ? Eigen::Vector3d(b_.body_half_length + b_.body_radius,
                                          b_.body_radius * 0.9, b_.body_radius) *
                              s
                        : Eigen::Vector3d(b_.body_radius, b_.body_half_length, 0) * s,
                    fur, false});
  parts_.push_back({"head", Shape::kSphere, Eigen::Vector3d(b_.head_radius, 0, 0) * s, fur, false});
  parts_.push_back(
      {"snout", Shape::kBox, Eigen::Vector3d(0.6, 0.45, 0.4) * b_.head_radius * s, "snout", false});
  for (const char* leg : {"leg_fl", "leg_fr", "leg_rl", "leg_rr"})
    parts_.push_back({leg, Shape::kCapsule,
                      Eigen::Vector3d(b_.leg_radius, b_.leg_length / 2, 0) * s, fur, false});
  parts_.push_back({"tail", Shape::kCapsule,
                    Eigen::Vector3d(b_.leg_radius * 0.6, b_.tail_length / 2, 0) * s, fur, false});
}

double QuadrupedActor::distance(double t) const {
  return offset_ + speed_ * std::max(0.0, t - start_time_);
}

Pose QuadrupedActor::root_pose(double t) const {
  double d = distance(t);
  return ground_pose(path_.position(d), 0.0, path_.heading(d));
}

namespace {

// A skinned model's bind bounds plus what its motion adds (legs swung
// forward and back, wings, a lifted head), in the root frame.
Eigen::AlignedBox3d with_model(Eigen::AlignedBox3d box, const ClipRig* rig, double scale,
                               double margin) {
  if (!rig) return box;
  const Eigen::AlignedBox3f& b = rig->model().bounds;
  box.extend(scale * b.min().cast<double>() - Eigen::Vector3d::Constant(margin));
  box.extend(scale * b.max().cast<double>() + Eigen::Vector3d::Constant(margin));
  return box;
}

}  // namespace

Eigen::AlignedBox3d QuadrupedActor::local_extent() const {
  const double s = scale_;
  const double front = b_.body_half_length + b_.body_radius + 2.5 * b_.head_radius;
  const double back = b_.body_half_length + b_.body_radius + b_.tail_length;
  const Eigen::AlignedBox3d box(
      Eigen::Vector3d(-back - 0.05, -0.3, 0.0) * s,
      Eigen::Vector3d(front + 0.05, 0.3, b_.body_height + 2.5 * b_.head_radius + 0.1) * s);
  return with_model(box, rig_.get(), mesh_scale_, 0.15);
}

void QuadrupedActor::pose_bones(double t, std::vector<Pose>& world_poses) const {
  world_poses.clear();
  if (!rig_) return;
  AnimalMotion m;
  m.walking = t >= start_time_ && speed_ > 0.0;
  m.cycles = (distance(t) - offset_) / (rig_->stride() * mesh_scale_) + gait_phase_ / (2.0 * M_PI);
  m.time = t;
  rig_->pose(m, root_pose(t), mesh_scale_, world_poses);
}

void QuadrupedActor::pose_parts(double t, std::vector<Pose>& out) const {
  const double s = scale_;
  const bool moving = t >= start_time_ && speed_ > 0.0;
  const double phi =
      moving ? 2.0 * M_PI * (distance(t) - offset_) / (b_.stride * s) + gait_phase_ : gait_phase_;
  const double amp = moving ? deg(28.0) : 0.0;
  const Pose root = root_pose(t);
  const double body_z = (b_.body_height + 0.015 * std::cos(2.0 * phi)) * s;
  const Eigen::Matrix3d r_body = rot_y(deg(2.0) * std::sin(2.0 * phi));
  std::vector<Pose> local(parts_.size());
  // Capsules lie along their z axis: turn the body capsule along x.
  local[0] = make_pose(Eigen::Matrix3d(r_body * (class_name_ == "pig" ? Eigen::Matrix3d::Identity()
                                                                      : rot_y(M_PI / 2))),
                       Eigen::Vector3d(0, 0, body_z));
  const double hx = (b_.body_half_length + b_.body_radius * 0.6) * s;
  const Eigen::Vector3d head(hx + b_.head_radius * s, 0,
                             body_z + 1.3 * b_.head_radius * s + 0.01 * std::sin(phi));
  local[1] = make_pose(rot_z(deg(10.0) * std::sin(0.5 * phi)), head);
  local[2] =
      make_pose(rot_z(deg(10.0) * std::sin(0.5 * phi)),
                head + Eigen::Vector3d(1.1 * b_.head_radius * s, 0, -0.25 * b_.head_radius * s));
  // Trot: diagonal legs move together.
  const double lx = b_.body_half_length * s, ly = b_.body_radius * 0.6 * s;
  const Eigen::Vector3d hips[4] = {
      {lx, ly, body_z}, {lx, -ly, body_z}, {-lx, ly, body_z}, {-lx, -ly, body_z}};
  const double swing[4] = {amp * std::sin(phi), amp * std::sin(phi + M_PI),
                           amp * std::sin(phi + M_PI), amp * std::sin(phi)};
  for (int i = 0; i < 4; ++i)
    local[3 + i] = limb(hips[i], Eigen::Matrix3d::Identity(), swing[i], b_.leg_length * s);
  const Eigen::Vector3d tail_root(-(b_.body_half_length + b_.body_radius * 0.8) * s, 0,
                                  body_z + 0.3 * b_.body_radius * s);
  const Eigen::Matrix3d r_tail = rot_z(deg(25.0) * std::sin(2.0 * phi + 0.5)) * rot_y(deg(-50.0));
  local[7] =
      make_pose(r_tail, tail_root + r_tail * Eigen::Vector3d(0, 0, 0.5 * b_.tail_length * s));
  out.resize(parts_.size());
  for (size_t i = 0; i < parts_.size(); ++i) out[i] = root * local[i];
}

// --------------------------------------------------------------------- bird

BirdActor::BirdActor(const ActorSpec& spec) {
  name_ = spec.name;
  class_name_ = "bird";
  Rng rng(spec.appearance);
  scale_ = spec.size * rng.uniform(0.9, 1.1);
  mesh_scale_ = spec.size;
  speed_ = spec.speed;
  offset_ = spec.start_offset;
  start_time_ = spec.start_time;
  height_ = spec.height;
  phase_ = rng.uniform(0.0, 2.0 * M_PI) + spec.gait_phase;
  path_ = actor_path(spec);
  const double s = scale_;
  const std::string feathers = "feathers_" + std::to_string(rng.below(2));
  parts_.push_back(
      {"body", Shape::kEllipsoid, Eigen::Vector3d(0.11, 0.055, 0.055) * s, feathers, false});
  parts_.push_back({"head", Shape::kSphere, Eigen::Vector3d(0.04, 0, 0) * s, feathers, false});
  parts_.push_back({"beak", Shape::kBox, Eigen::Vector3d(0.025, 0.01, 0.008) * s, "beak", false});
  parts_.push_back(
      {"wing_l", Shape::kBox, Eigen::Vector3d(0.07, 0.13, 0.006) * s, feathers, false});
  parts_.push_back(
      {"wing_r", Shape::kBox, Eigen::Vector3d(0.07, 0.13, 0.006) * s, feathers, false});
  parts_.push_back({"tail", Shape::kBox, Eigen::Vector3d(0.07, 0.04, 0.004) * s, feathers, false});
}

Pose BirdActor::root_pose(double t) const {
  double d = offset_ + speed_ * std::max(0.0, t - start_time_);
  double z = height_ + 0.08 * std::sin(2.0 * M_PI * t / 1.7 + phase_);
  return ground_pose(path_.position(d), z, path_.heading(d));
}

Eigen::AlignedBox3d BirdActor::local_extent() const {
  const double s = scale_;
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-0.3, -0.32, -0.2) * s,
                                Eigen::Vector3d(0.3, 0.32, 0.2) * s);
  return with_model(box, rig_.get(), mesh_scale_, 0.3);
}

void BirdActor::pose_bones(double t, std::vector<Pose>& world_poses) const {
  world_poses.clear();
  if (!rig_) return;
  AnimalMotion m;
  m.time = t + phase_;
  // The model's bind pose stands on z = 0: lift its body to the flight height.
  Pose root = root_pose(t);
  root.translation().z() -= 0.5 * mesh_scale_ * rig_->model().bounds.max().z();
  rig_->pose(m, root, mesh_scale_, world_poses);
}

void BirdActor::pose_parts(double t, std::vector<Pose>& out) const {
  const double s = scale_;
  const double flap = deg(45.0) * std::sin(2.0 * M_PI * 5.0 * t + phase_);
  const Pose root = root_pose(t);
  std::vector<Pose> local(parts_.size());
  local[0] = Pose::Identity();
  local[1] = make_pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.12, 0, 0.04) * s);
  local[2] = make_pose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.175, 0, 0.035) * s);
  for (int i = 0; i < 2; ++i) {
    const double side = i == 0 ? 1.0 : -1.0;
    const Eigen::Matrix3d r = rot_x(side * flap);
    local[3 + i] = make_pose(r, Eigen::Vector3d(0, side * 0.045 * s, 0.02 * s) +
                                    r * Eigen::Vector3d(0, side * 0.13 * s, 0));
  }
  local[5] = make_pose(rot_y(deg(10.0)), Eigen::Vector3d(-0.16, 0, 0.01) * s);
  out.resize(parts_.size());
  for (size_t i = 0; i < parts_.size(); ++i) out[i] = root * local[i];
}

}  // namespace depot::sim
