#pragma once
// The materials of an assimp scene as AssetMaterial: base colour and the
// texture image, decoded from the file's embedded bytes or read from a file
// beside the model. Part of the loader (asset_loader.h); separate because
// texture lookup and decoding is its own concern.
#include <string>
#include <vector>

#include "sim/assets/asset_model.h"

struct aiScene;

namespace depot::sim {

// One AssetMaterial per scene material, same order. Fails naming
// `model_path` when a texture is neither embedded nor found as a file
// (relative to the model's folder, or by its bare name there) or does not
// decode.
std::vector<AssetMaterial> read_materials(const aiScene& scene, const std::string& model_path,
                                          bool linear_colours);

// sRGB encoding of a linear colour channel (0..1).
float linear_to_srgb(float linear);

}  // namespace depot::sim
