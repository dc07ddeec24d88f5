#pragma once
// Loads glTF/GLB, FBX and OBJ models with assimp into the plain data of
// asset_model.h: triangles, normals, UVs, bone weights, materials with their
// textures decoded (embedded or beside the file), the skeleton and the
// animation clips, all turned into the simulator's model frame (z up, x
// forward, metres, standing on z = 0).
//
// Every failure is one depot::Error "<model file>: <problem>": a missing,
// unreadable, corrupt or unsupported file, a model without triangles, a
// texture file that is not there or does not decode, a requested clip the
// file does not have.
#include <string>
#include <vector>

#include "sim/assets/asset_model.h"
#include "sim/assets/axes.h"

namespace depot::sim {

struct AssetLoadOptions {
  // The file's axes: which way is up and which way the model faces. glTF is
  // +y up by specification; where a model faces is per file.
  Axis up = Axis::kPosY;
  Axis forward = Axis::kPosZ;
  // Metres per file unit, used when target_height is 0.
  double scale = 1.0;
  // > 0: scale so that the bind pose is this tall (m) instead; for files in
  // arbitrary units (the Quaternius FBX animals are ~5 units tall).
  double target_height = 0.0;
  // Centre the bind pose's footprint (bounding box) on x = y = 0. Off by
  // default: rigs put their origin under the body, between the feet, which
  // is where the actor's root pose should hold them. The model always stands
  // on z = 0.
  bool center_xy = false;
  // Keep only these clips, failing when one is missing; empty keeps all.
  std::vector<std::string> clips;
  // Material colours in the file are linear (glTF's baseColorFactor, and the
  // Blender FBX exports): encode them to sRGB for MuJoCo, which does no
  // colour management.
  bool linear_colours = true;
  // Drop the triangles of alpha-masked materials that are transparent where
  // they sample their texture (alpha_cutout.h), since MuJoCo 2.2 would draw
  // them opaque.
  bool cut_alpha = true;
};

AssetModel load_asset(const std::string& path, const AssetLoadOptions& options = {});

// Adds the clips `names` of another file whose skeleton shares bone names
// with `model` (the dog's clips live in fox-animations.glb). Channels are
// matched by bone name and dropped for bones the model lacks; translations
// are scaled by model.scale. `rotations_only` keeps just the rotation keys,
// for a rig whose proportions differ from the model's. The other file must
// use the same axes as the model's. Fails naming `path` for a missing file or
// clip, or when no channel matches a bone of the model.
void load_clips_into(AssetModel& model, const std::string& path,
                     const std::vector<std::string>& names, bool rotations_only);

// Model file extensions the loader accepts (lower case, with the dot).
const std::vector<std::string>& supported_model_extensions();

}  // namespace depot::sim
