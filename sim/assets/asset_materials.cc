#include "sim/assets/asset_materials.h"

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error.h"

namespace fs = std::filesystem;

namespace depot::sim {
namespace {

// 8-bit BGR, or BGRA when some texel is not fully opaque.
cv::Mat to_bgr_or_bgra(const cv::Mat& decoded) {
  cv::Mat img = decoded;
  if (img.depth() != CV_8U) img.convertTo(img, CV_8U, img.depth() == CV_16U ? 1.0 / 257.0 : 1.0);
  if (img.channels() == 1) cv::cvtColor(img, img, cv::COLOR_GRAY2BGR);
  if (img.channels() == 4) {
    double min_alpha = 255;
    cv::Mat alpha;
    cv::extractChannel(img, alpha, 3);
    cv::minMaxLoc(alpha, &min_alpha);
    // An alpha channel that is opaque everywhere carries nothing.
    if (min_alpha >= 255) cv::cvtColor(img, img, cv::COLOR_BGRA2BGR);
  }
  return img;
}

cv::Mat decode_embedded(const aiTexture& tex, const std::string& model_path,
                        const std::string& name) {
  cv::Mat decoded;
  if (tex.mHeight == 0) {
    // Compressed (PNG, JPEG...): mWidth is the byte count.
    const auto* bytes = reinterpret_cast<const uchar*>(tex.pcData);
    decoded = cv::imdecode(std::vector<uchar>(bytes, bytes + tex.mWidth), cv::IMREAD_UNCHANGED);
  } else {
    // Raw texels; aiTexel is b, g, r, a like OpenCV's BGRA.
    cv::Mat raw(static_cast<int>(tex.mHeight), static_cast<int>(tex.mWidth), CV_8UC4,
                const_cast<aiTexel*>(tex.pcData));
    decoded = raw.clone();
  }
  if (decoded.empty()) fail(model_path, "embedded texture '" + name + "' does not decode");
  return decoded;
}

cv::Mat read_texture_file(const std::string& model_path, const std::string& name,
                          const std::string& material) {
  const fs::path dir = fs::path(model_path).parent_path();
  std::string reference = name;
  std::replace(reference.begin(), reference.end(), '\\', '/');
  // As written (relative to the model), then by bare name beside the model:
  // exporters often store the artist's absolute paths.
  std::vector<fs::path> candidates = {dir / reference, dir / fs::path(reference).filename()};
  if (fs::path(reference).is_absolute()) candidates.insert(candidates.begin(), reference);
  for (const auto& c : candidates) {
    if (!fs::is_regular_file(c)) continue;
    cv::Mat decoded = cv::imread(c.string(), cv::IMREAD_UNCHANGED);
    if (decoded.empty()) fail(model_path, "texture file '" + c.string() + "' does not decode");
    return decoded;
  }
  fail(model_path, "texture '" + name + "' of material '" + material + "' not found (looked for " +
                       candidates.back().string() + ")");
}

Eigen::Vector4f base_colour(const aiMaterial& mat, bool linear) {
  aiColor4D c(1, 1, 1, 1);
  // glTF's baseColorFactor when present, else the classic diffuse colour.
  if (mat.Get(AI_MATKEY_BASE_COLOR, c) != AI_SUCCESS) {
    c = aiColor4D(1, 1, 1, 1);
    mat.Get(AI_MATKEY_COLOR_DIFFUSE, c);
  }
  float opacity = 1.0f;
  if (mat.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS) c.a *= opacity;
  Eigen::Vector4f rgba(c.r, c.g, c.b, c.a);
  for (int i = 0; i < 3; ++i) {
    rgba[i] = std::clamp(rgba[i], 0.0f, 1.0f);
    if (linear) rgba[i] = linear_to_srgb(rgba[i]);
  }
  rgba[3] = std::clamp(rgba[3], 0.0f, 1.0f);
  return rgba;
}

}  // namespace

float linear_to_srgb(float x) {
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

std::vector<AssetMaterial> read_materials(const aiScene& scene, const std::string& model_path,
                                          bool linear_colours) {
  std::vector<AssetMaterial> out;
  // One decode per texture that several materials share: key -> (image, name).
  std::map<std::string, std::pair<cv::Mat, std::string>> decoded;
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
    const aiMaterial& mat = *scene.mMaterials[i];
    AssetMaterial m;
    m.name = mat.GetName().C_Str();
    m.rgba = base_colour(mat, linear_colours);

    aiString tex_path;
    bool has_texture = mat.GetTexture(aiTextureType_BASE_COLOR, 0, &tex_path) == AI_SUCCESS ||
                       mat.GetTexture(aiTextureType_DIFFUSE, 0, &tex_path) == AI_SUCCESS;
    if (has_texture && tex_path.length > 0) {
      const std::string key = tex_path.C_Str();
      auto it = decoded.find(key);
      if (it == decoded.end()) {
        const aiTexture* embedded = scene.GetEmbeddedTexture(key.c_str());
        cv::Mat img = embedded ? decode_embedded(*embedded, model_path, key)
                               : read_texture_file(model_path, key, m.name);
        const std::string name =
            embedded && embedded->mFilename.length > 0 ? embedded->mFilename.C_Str() : key;
        it = decoded.emplace(key, std::make_pair(to_bgr_or_bgra(img), name)).first;
      }
      m.texture = it->second.first;
      m.texture_name = it->second.second;
      m.texture_has_alpha = m.texture.channels() == 4;
    }

    aiString alpha_mode;
    if (mat.Get(AI_MATKEY_GLTF_ALPHAMODE, alpha_mode) == AI_SUCCESS) {
      const std::string mode = alpha_mode.C_Str();
      m.alpha_mask = mode == "MASK" || mode == "BLEND";
      float cutoff = 0.5f;
      if (mode == "MASK" && mat.Get(AI_MATKEY_GLTF_ALPHACUTOFF, cutoff) == AI_SUCCESS)
        m.alpha_cutoff = cutoff;
    } else {
      // Formats without an alpha mode: a texture with transparent texels is
      // meant as a cut-out.
      m.alpha_mask = m.texture_has_alpha;
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace depot::sim
