#include "sim/assets/skinning.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace depot::sim {
namespace {

// Index of the last key at or before t (0 when t precedes every key).
template <typename T>
size_t key_before(const std::vector<Key<T>>& keys, double t) {
  auto it = std::upper_bound(keys.begin(), keys.end(), t,
                             [](double time, const Key<T>& k) { return time < k.time; });
  return it == keys.begin() ? 0 : static_cast<size_t>(it - keys.begin()) - 1;
}

// Fraction of the way from key i to key i + 1 at time t.
template <typename T>
double key_fraction(const std::vector<Key<T>>& keys, size_t i, double t) {
  if (i + 1 >= keys.size()) return 0.0;
  const double span = keys[i + 1].time - keys[i].time;
  return span > 0 ? std::clamp((t - keys[i].time) / span, 0.0, 1.0) : 0.0;
}

Eigen::Vector3d sample(const std::vector<Key<Eigen::Vector3d>>& keys, double t) {
  const size_t i = key_before(keys, t);
  const double s = key_fraction(keys, i, t);
  if (s <= 0) return keys[i].value;
  return (1.0 - s) * keys[i].value + s * keys[i + 1].value;
}

Eigen::Quaterniond sample(const std::vector<Key<Eigen::Quaterniond>>& keys, double t) {
  const size_t i = key_before(keys, t);
  const double s = key_fraction(keys, i, t);
  if (s <= 0) return keys[i].value;
  // Eigen's slerp takes the shorter arc.
  return keys[i].value.slerp(s, keys[i + 1].value).normalized();
}

Eigen::Affine3d compose(const Eigen::Vector3d& t, const Eigen::Quaterniond& r,
                        const Eigen::Vector3d& s) {
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  a.linear() = r.toRotationMatrix() * s.asDiagonal();
  a.translation() = t;
  return a;
}

}  // namespace

SkeletonPose rest_pose(const Skeleton& skeleton) {
  SkeletonPose pose;
  for (const Bone& b : skeleton.bones) {
    pose.translation.push_back(b.rest_translation);
    pose.rotation.push_back(b.rest_rotation);
    pose.scale.push_back(b.rest_scale);
  }
  return pose;
}

void sample_clip(const AnimationClip& clip, double t, bool loop, SkeletonPose& pose) {
  if (clip.duration > 0) {
    t = loop ? t - clip.duration * std::floor(t / clip.duration)
             : std::clamp(t, 0.0, clip.duration);
  } else {
    t = 0;
  }
  for (const BoneChannel& ch : clip.channels) {
    if (ch.bone < 0 || ch.bone >= static_cast<int>(pose.rotation.size())) continue;
    if (!ch.translations.empty()) pose.translation[ch.bone] = sample(ch.translations, t);
    if (!ch.rotations.empty()) pose.rotation[ch.bone] = sample(ch.rotations, t);
    if (!ch.scales.empty()) pose.scale[ch.bone] = sample(ch.scales, t);
  }
}

void bone_globals(const Skeleton& skeleton, const SkeletonPose& pose,
                  std::vector<Eigen::Affine3d>& globals) {
  const size_t n = skeleton.bones.size();
  globals.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const int p = skeleton.bones[i].parent;  // parents come first
    const Eigen::Affine3d local = compose(pose.translation[i], pose.rotation[i], pose.scale[i]);
    globals[i] = (p >= 0 ? globals[p] : skeleton.root) * local;
  }
}

std::vector<int> find_bones(const Skeleton& skeleton, const std::vector<std::string>& names,
                            const std::string& where) {
  std::vector<int> out;
  for (const auto& name : names) {
    const int b = find_bone(skeleton, name);
    if (b < 0) fail(where, "the skeleton has no bone named '" + name + "'");
    out.push_back(b);
  }
  return out;
}

void set_bone_rotation(SkeletonPose& pose, int bone, const Eigen::Quaterniond& local) {
  pose.rotation.at(bone) = local.normalized();
}

void turn_bone(const Skeleton& skeleton, SkeletonPose& pose, int bone,
               const Eigen::Quaterniond& turn) {
  const Bone& b = skeleton.bones.at(bone);
  // The parent's rest orientation in the model frame (its global carries the
  // file's unit scale; only the rotation matters here).
  const Eigen::Affine3d parent_rest =
      b.parent >= 0 ? skeleton.bones[b.parent].inverse_bind.inverse() : skeleton.root;
  const Eigen::Quaterniond p(parent_rest.rotation());
  pose.rotation[bone] = (p.conjugate() * turn * p * b.rest_rotation).normalized();
}

std::vector<int> deforming_bones(const Skeleton& skeleton) {
  std::vector<int> bones;
  for (size_t b = 0; b < skeleton.bones.size(); ++b)
    if (skeleton.bones[b].deforms) bones.push_back(static_cast<int>(b));
  return bones;
}

Eigen::Vector3d rest_joint_position(const Skeleton& skeleton, int bone) {
  return skeleton.bones.at(bone).inverse_bind.inverse().translation();
}

}  // namespace depot::sim
