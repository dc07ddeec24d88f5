#pragma once
// MJCF for a person or animal drawn as a skinned catalogue model: the
// textures and materials of a variant (shared by every actor wearing it), one
// mocap body per deforming bone, and one <skin> per material submesh hanging
// from those bodies. MuJoCo 2.2.2 deforms skins at draw time from the bodies' poses and
// draws them in the segmentation pass as mjOBJ_SKIN (sim/assets/README.md),
// so posing the bodies is all a frame costs and labels stay exact.
#include <string>
#include <utility>
#include <vector>

#include "common/pose.h"
#include "sim/assets/asset_model.h"

namespace depot::sim {

// Textures and materials of one model, without its meshes (skins carry their
// own vertices): VFS files and <asset> elements, and the material name of
// every mesh ("" for none).
struct SkinMaterials {
  std::vector<std::pair<std::string, std::string>> files;
  std::string asset_xml;
  std::vector<std::string> material_names;
};
SkinMaterials encode_skin_materials(const AssetModel& model, const std::string& prefix);

// Mocap bodies (for <worldbody>) of the model's `body_bones` (the rig's
// deforming bones) at `poses` (world), named `prefix`/<bone>; their names go
// to `bodies`.
std::string bone_bodies_xml(const AssetModel& model, const std::vector<int>& body_bones,
                            const std::vector<Pose>& poses, const std::string& prefix,
                            std::vector<std::string>& bodies);

// <skin> elements (for <asset>), one per mesh with triangles, named
// `prefix`/skin<i>; `bodies` as bone_bodies_xml returned them. Skin names
// go to `skins`.
// The skin is the model scaled by `scale` about its origin (world_bone_poses
// with the same scale poses its bodies).
std::string skins_xml(const AssetModel& model, const std::vector<int>& body_bones, double scale,
                      const std::vector<std::string>& material_names,
                      const std::vector<std::string>& bodies, const std::string& prefix,
                      std::vector<std::string>& skins);

}  // namespace depot::sim
