#include "sim/actors/human.h"

#include <algorithm>
#include <cmath>

#include "common/rng.h"
#include "sim/actors/crowd.h"
#include "sim/actors/limb.h"

namespace depot::sim {
namespace {

enum Part {
  kPelvis,
  kTorso,
  kHead,
  kHair,
  kThighL,
  kShinL,
  kFootL,
  kThighR,
  kShinR,
  kFootR,
  kUpperArmL,
  kForearmL,
  kUpperArmR,
  kForearmR,
  kPusher
};

// Segment lengths for a 1.75 m person.
constexpr double kThigh = 0.44, kShin = 0.44, kUpperArm = 0.30, kForearm = 0.28;
constexpr double kAnkleHeight = 0.07;

}  // namespace

HumanActor::HumanActor(const ActorSpec& spec, const SeatPose* seat) {
  name_ = spec.name;
  class_name_ = "person";
  Rng rng(spec.appearance);
  scale_ = spec.size * rng.uniform(0.92, kLargestScale);
  mesh_scale_ = spec.size;
  speed_ = spec.speed;
  offset_ = spec.start_offset;
  start_time_ = spec.start_time;
  phase_ = rng.uniform(0.0, 2.0 * M_PI);
  gait_phase_ = spec.gait_phase;
  if (spec.action == "sit") {
    mode_ = Mode::kSit;
    if (seat) seat_ = *seat;
  } else if (spec.action == "crowd") {
    mode_ = Mode::kCrowd;
    track_ = spec.track;
  } else if (spec.action == "carry") {
    mode_ = Mode::kCarry;
    path_ = actor_path(spec);
    carry_ = std::make_shared<CarryMotion>(spec, path_, scale_);
  } else {
    mode_ = spec.action == "push" ? Mode::kPush : Mode::kWalk;
    path_ = actor_path(spec);
  }

  const std::string shirt = "shirt_" + std::to_string(rng.below(6));
  const std::string pants = "pants_" + std::to_string(rng.below(3));
  const std::string skin = "skin_" + std::to_string(rng.below(3));
  const std::string hair = "hair_" + std::to_string(rng.below(2));
  const double s = scale_;
  auto add = [&](const std::string& n, Shape shape, Eigen::Vector3d size, const std::string& mat) {
    parts_.push_back({n, shape, size * s, mat, false});
  };
  // Order matches enum Part.
  add("pelvis", Shape::kBox, {0.11, 0.17, 0.08}, pants);
  add("torso", Shape::kBox, {0.12, 0.19, 0.25}, shirt);
  add("head", Shape::kSphere, {0.11, 0, 0}, skin);
  add("hair", Shape::kEllipsoid, {0.105, 0.105, 0.08}, hair);
  for (std::string side : {"l", "r"}) {
    add("thigh_" + side, Shape::kCapsule, {0.075, kThigh / 2, 0}, pants);
    add("shin_" + side, Shape::kCapsule, {0.058, kShin / 2, 0}, pants);
    add("foot_" + side, Shape::kBox, {0.12, 0.05, 0.035}, "shoes");
  }
  for (std::string side : {"l", "r"}) {
    add("upperarm_" + side, Shape::kCapsule, {0.05, kUpperArm / 2, 0}, shirt);
    add("forearm_" + side, Shape::kCapsule, {0.042, kForearm / 2, 0}, skin);
  }
  if (mode_ == Mode::kPush) {
    // Hand height of the plate is low (0.3-0.62 m): it pushes seats and cart
    // frames near their centre of mass, so they slide rather than tip.
    parts_.push_back({"pusher", Shape::kBox, push_plate_half(s), "", true});
  }
}

Eigen::Vector3d HumanActor::push_plate_centre(double scale) {
  return Eigen::Vector3d(0.42, 0.0, 0.46) * scale;
}

Eigen::Vector3d HumanActor::push_plate_half(double scale) {
  return Eigen::Vector3d(0.05, 0.26, 0.16) * scale;
}

double HumanActor::distance(double t) const {
  return offset_ + speed_ * std::max(0.0, t - start_time_);
}

std::unique_ptr<Actor> HumanActor::make_carried_goods() const {
  if (!carry_) return nullptr;
  return std::make_unique<CarriedGoods>(name_, carry_);
}

Pose HumanActor::root_pose(double t) const {
  if (mode_ == Mode::kSit) return ground_pose(seat_.position, 0.0, seat_.yaw);
  if (mode_ == Mode::kCarry) return carry_->carrier_root(t);
  if (mode_ == Mode::kCrowd) {
    const TrackPoint p = track_at(track_, t);
    return ground_pose(p.xy, 0.0, p.heading);
  }
  double d = distance(t);
  return ground_pose(path_.position(d), 0.0, path_.heading(d));
}

Eigen::AlignedBox3d HumanActor::local_extent() const {
  const double s = scale_;
  Eigen::AlignedBox3d box(Eigen::Vector3d(-0.6, -0.5, 0.0) * s,
                          Eigen::Vector3d(0.95, 0.5, 2.0) * s);
  if (rig_) {
    // The model's bind bounds (A-pose arms are wider than the primitives'),
    // plus what the gait adds: a leg or arm swung forward, a seated person's
    // thighs.
    const Eigen::AlignedBox3f& b = rig_->model().bounds;
    box.extend(mesh_scale_ * b.min().cast<double>() - Eigen::Vector3d(0.3, 0.1, 0.0));
    box.extend(mesh_scale_ * b.max().cast<double>() + Eigen::Vector3d(0.6, 0.1, 0.1));
  }
  return box;
}

HumanPosture HumanActor::posture(double t) const {
  HumanPosture p;
  if (mode_ == Mode::kSit) {
    // Seated: thighs forward on the seat, shins down, slow head and arm motions.
    const double w = 2.0 * M_PI;
    for (int i = 0; i < 2; ++i) {
      p.hip[i] = deg(85.0);
      p.knee[i] = deg(75.0 + 4.0 * std::sin(w * t / 7.1 + phase_ + i));
      p.shoulder[i] = deg(35.0 + 10.0 * std::sin(w * t / 2.9 + phase_ + 1.7 * i));
      p.elbow[i] = deg(55.0 + 12.0 * std::sin(w * t / 2.3 + phase_ + 0.9 * i));
    }
    p.torso_pitch = deg(-3.0 + 2.5 * std::sin(w * t / 6.1 + phase_));
    p.torso_yaw = deg(3.0 * std::sin(w * t / 8.3 + phase_));
    p.head_yaw = deg(14.0 * std::sin(w * t / 5.3 + phase_));
    p.head_pitch = deg(6.0 + 6.0 * std::sin(w * t / 3.7 + phase_));
    p.seated = true;
    p.seat_height = seat_.seat_height;
    return p;
  }
  // Walking: phase advances with distance (stride 1.35 m per full cycle).
  // A carrier stands still while it lifts, sets down or waits.
  const CarryState carry = carry_ ? carry_->at(t) : CarryState{};
  // A crowd's walker moves as its track says (slowing, stopping, turning).
  const bool track_moving =
      mode_ == Mode::kCrowd &&
      track_at(track_, t + 0.1).walked - track_at(track_, t - 0.1).walked > 0.02;
  const bool moving = mode_ == Mode::kCrowd ? track_moving
                                            : t >= start_time_ && speed_ > 0.0 &&
                                                  (mode_ != Mode::kCarry || carry.lift >= 1.0);
  const double stride = 1.35 * scale_;
  const double walked = mode_ == Mode::kCarry   ? carry.distance
                        : mode_ == Mode::kCrowd ? track_at(track_, t).walked
                                                : distance(t) - offset_;
  const double phi = moving ? 2.0 * M_PI * walked / stride + gait_phase_ : gait_phase_;
  const double amp = moving ? deg(22.0) * std::clamp(speed_ / 1.2, 0.6, 1.3) : 0.0;
  p.hip[0] = amp * std::sin(phi);
  p.hip[1] = -amp * std::sin(phi);
  p.knee[0] = deg(4.0) + (moving ? deg(50.0) * std::pow(std::max(0.0, std::cos(phi)), 2) : 0.0);
  p.knee[1] = deg(4.0) + (moving ? deg(50.0) * std::pow(std::max(0.0, -std::cos(phi)), 2) : 0.0);
  if (mode_ == Mode::kPush) {
    // Hands on the chair's or cart's back (about 1 m up, 0.4 m ahead): upper
    // arms 40 deg forward, forearms 20 deg further.
    for (int i = 0; i < 2; ++i) {
      p.shoulder[i] = deg(40.0) + 0.1 * amp * std::sin(phi + i * M_PI);
      p.elbow[i] = deg(20.0);
    }
    p.torso_pitch = deg(12.0);
  } else if (mode_ == Mode::kCarry && (carry.lift > 0.0 || carry.bend > 0.0)) {
    // Goods held at the waist: upper arms a little forward, forearms level;
    // bending down to a support, the torso and arms reach for it.
    for (int i = 0; i < 2; ++i) {
      p.shoulder[i] = deg(20.0) + deg(35.0) * carry.bend;
      p.elbow[i] = deg(50.0) - deg(30.0) * carry.bend;
    }
    p.torso_pitch = deg(4.0) + deg(40.0) * carry.bend;
  } else {
    p.shoulder[0] = -0.8 * amp * std::sin(phi);
    p.shoulder[1] = 0.8 * amp * std::sin(phi);
    p.elbow[0] = deg(15.0) + 0.5 * std::max(0.0, p.shoulder[0]);
    p.elbow[1] = deg(15.0) + 0.5 * std::max(0.0, p.shoulder[1]);
    p.torso_pitch = deg(4.0);
  }
  p.torso_yaw = 0.25 * amp * std::sin(phi);
  p.head_yaw = -p.torso_yaw;
  return p;
}

void HumanActor::pose_bones(double t, std::vector<Pose>& world_poses) const {
  if (!rig_) {
    world_poses.clear();
    return;
  }
  rig_->pose(posture(t), root_pose(t), mesh_scale_, world_poses);
}

void HumanActor::pose_parts(double t, std::vector<Pose>& out) const {
  const double s = scale_;
  const HumanPosture p = posture(t);
  double pelvis_z = 0.0;
  if (p.seated) {
    pelvis_z = seat_.seat_height + 0.08 * s;
  } else {
    // The pelvis rides on the longer (stance) leg: its height bobs naturally.
    double reach = 0.0;
    for (int i = 0; i < 2; ++i)
      reach = std::max(reach, kThigh * std::cos(p.hip[i]) + kShin * std::cos(p.hip[i] - p.knee[i]));
    pelvis_z = (reach + kAnkleHeight + 0.05) * s;
  }

  const Pose root = root_pose(t);
  std::vector<Pose> local(parts_.size(), Pose::Identity());
  const Eigen::Matrix3d r_pelvis = rot_z(0.5 * p.torso_yaw);
  const Eigen::Vector3d pelvis(-0.02 * s, 0, pelvis_z);
  local[kPelvis] = make_pose(r_pelvis, pelvis);
  for (int i = 0; i < 2; ++i) {
    const double side = i == 0 ? 1.0 : -1.0;
    Eigen::Vector3d hip = pelvis + r_pelvis * Eigen::Vector3d(0, side * 0.09 * s, -0.05 * s);
    Eigen::Vector3d knee, ankle;
    local[kThighL + 3 * i] = limb(hip, r_pelvis, p.hip[i], kThigh * s, &knee);
    local[kShinL + 3 * i] = limb(knee, r_pelvis, p.hip[i] - p.knee[i], kShin * s, &ankle);
    local[kFootL + 3 * i] =
        make_pose(r_pelvis, ankle + r_pelvis * Eigen::Vector3d(0.05 * s, 0, -0.035 * s));
  }
  const Eigen::Matrix3d r_torso = r_pelvis * rot_z(0.5 * p.torso_yaw) * rot_y(p.torso_pitch);
  local[kTorso] = make_pose(r_torso, pelvis + r_torso * Eigen::Vector3d(0, 0, 0.33 * s));
  for (int i = 0; i < 2; ++i) {
    const double side = i == 0 ? 1.0 : -1.0;
    Eigen::Vector3d shoulder = pelvis + r_torso * Eigen::Vector3d(0, side * 0.235 * s, 0.53 * s);
    Eigen::Vector3d elbow;
    local[kUpperArmL + 2 * i] = limb(shoulder, r_torso, p.shoulder[i], kUpperArm * s, &elbow);
    local[kForearmL + 2 * i] = limb(elbow, r_torso, p.shoulder[i] + p.elbow[i], kForearm * s);
  }
  const Eigen::Matrix3d r_head = r_torso * rot_z(p.head_yaw) * rot_y(p.head_pitch);
  const Eigen::Vector3d neck = pelvis + r_torso * Eigen::Vector3d(0, 0, 0.60 * s);
  const Eigen::Vector3d head = neck + r_head * Eigen::Vector3d(0, 0, 0.12 * s);
  local[kHead] = make_pose(r_head, head);
  local[kHair] = make_pose(r_head, head + r_head * Eigen::Vector3d(-0.02 * s, 0, 0.045 * s));
  if (mode_ == Mode::kPush)
    local[kPusher] = make_pose(Eigen::Matrix3d::Identity(), push_plate_centre(s));

  out.resize(parts_.size());
  for (size_t i = 0; i < parts_.size(); ++i) out[i] = root * local[i];
}

}  // namespace depot::sim
