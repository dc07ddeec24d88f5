#include "sim/assets/asset_model.h"

namespace depot::sim {

int find_bone(const Skeleton& skeleton, const std::string& name) {
  for (size_t i = 0; i < skeleton.bones.size(); ++i)
    if (skeleton.bones[i].name == name) return static_cast<int>(i);
  return -1;
}

int find_clip(const AssetModel& model, const std::string& name) {
  for (size_t i = 0; i < model.clips.size(); ++i)
    if (model.clips[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace depot::sim
