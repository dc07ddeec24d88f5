#include "sim/assets/alpha_cutout.h"

#include <cmath>

namespace depot::sim {
namespace {

float alpha_at(const cv::Mat& bgra, const Eigen::Vector2f& uv) {
  // Nearest texel, repeating like GL_REPEAT; v = 0 is the image's top row.
  const float u = uv.x() - std::floor(uv.x()), v = uv.y() - std::floor(uv.y());
  const int x = std::min(bgra.cols - 1, static_cast<int>(u * bgra.cols));
  const int y = std::min(bgra.rows - 1, static_cast<int>(v * bgra.rows));
  return bgra.at<cv::Vec4b>(y, x)[3] / 255.0f;
}

bool cuttable(const AssetMaterial& m) {
  return m.alpha_mask && m.texture_has_alpha && m.texture.type() == CV_8UC4;
}

// Transparent texels take the mean colour of the opaque ones (alpha kept).
void fill_transparent_colour(cv::Mat& bgra, float cutoff) {
  cv::Vec3d sum(0, 0, 0);
  double count = 0;
  const int threshold = static_cast<int>(std::lround(cutoff * 255.0f));
  for (int y = 0; y < bgra.rows; ++y) {
    const auto* row = bgra.ptr<cv::Vec4b>(y);
    for (int x = 0; x < bgra.cols; ++x) {
      if (row[x][3] < threshold) continue;
      sum += cv::Vec3d(row[x][0], row[x][1], row[x][2]);
      count += 1;
    }
  }
  if (count == 0) return;
  const cv::Vec3b mean(cv::saturate_cast<uchar>(sum[0] / count),
                       cv::saturate_cast<uchar>(sum[1] / count),
                       cv::saturate_cast<uchar>(sum[2] / count));
  for (int y = 0; y < bgra.rows; ++y) {
    auto* row = bgra.ptr<cv::Vec4b>(y);
    for (int x = 0; x < bgra.cols; ++x)
      if (row[x][3] < threshold) row[x] = cv::Vec4b(mean[0], mean[1], mean[2], row[x][3]);
  }
}

// Removes vertices no triangle uses, renumbering the triangles.
void drop_unused_vertices(AssetMesh& m) {
  std::vector<int> remap(m.positions.size(), -1);
  int next = 0;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      if (remap[t[k]] < 0) remap[t[k]] = next++;
  auto compact = [&](auto& values) {
    if (values.empty()) return;
    std::remove_reference_t<decltype(values)> kept(next);
    for (size_t v = 0; v < remap.size(); ++v)
      if (remap[v] >= 0) kept[remap[v]] = values[v];
    values.swap(kept);
  };
  compact(m.positions);
  compact(m.normals);
  compact(m.uvs);
  compact(m.bones);
  for (auto& t : m.triangles) t = Eigen::Vector3i(remap[t[0]], remap[t[1]], remap[t[2]]);
}

}  // namespace

float triangle_alpha(const AssetMesh& mesh, const AssetMaterial& material, int triangle) {
  if (!cuttable(material) || mesh.uvs.empty()) return 1.0f;
  const Eigen::Vector3i& t = mesh.triangles[triangle];
  const Eigen::Vector2f a = mesh.uvs[t[0]], b = mesh.uvs[t[1]], c = mesh.uvs[t[2]];
  const Eigen::Vector2f samples[7] = {
      a, b, c, 0.5f * (a + b), 0.5f * (b + c), 0.5f * (c + a), (a + b + c) / 3.0f};
  float sum = 0;
  for (const auto& uv : samples) sum += alpha_at(material.texture, uv);
  return sum / 7.0f;
}

int cut_alpha_triangles(AssetModel& model) {
  int dropped = 0;
  for (AssetMesh& mesh : model.meshes) {
    if (mesh.material < 0) continue;
    const AssetMaterial& mat = model.materials[mesh.material];
    if (!cuttable(mat) || mesh.uvs.empty()) continue;
    std::vector<Eigen::Vector3i> kept;
    for (size_t i = 0; i < mesh.triangles.size(); ++i)
      if (triangle_alpha(mesh, mat, static_cast<int>(i)) >= mat.alpha_cutoff)
        kept.push_back(mesh.triangles[i]);
    dropped += static_cast<int>(mesh.triangles.size() - kept.size());
    mesh.triangles.swap(kept);
    drop_unused_vertices(mesh);
  }
  for (AssetMaterial& mat : model.materials)
    if (cuttable(mat)) fill_transparent_colour(mat.texture, mat.alpha_cutoff);
  return dropped;
}

}  // namespace depot::sim
