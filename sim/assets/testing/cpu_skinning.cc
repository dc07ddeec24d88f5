#include "sim/assets/testing/cpu_skinning.h"

namespace depot::sim::testing {

void skinning_matrices(const Skeleton& skeleton, const std::vector<Eigen::Affine3d>& globals,
                       std::vector<Eigen::Affine3d>& matrices) {
  matrices.resize(skeleton.bones.size());
  for (size_t i = 0; i < skeleton.bones.size(); ++i)
    matrices[i] = globals[i] * skeleton.bones[i].inverse_bind;
}

void skin_mesh(const AssetMesh& mesh, const std::vector<Eigen::Affine3d>& matrices,
               std::vector<Eigen::Vector3f>& positions, std::vector<Eigen::Vector3f>& normals) {
  const size_t n = mesh.positions.size();
  const bool has_normals = mesh.normals.size() == n;
  positions.resize(n);
  normals.resize(has_normals ? n : 0);
  if (mesh.bones.empty()) {
    positions = mesh.positions;
    normals = mesh.normals;
    return;
  }
  // Single precision, like the vertices: 3x4 blends per vertex.
  std::vector<Eigen::Matrix<float, 3, 4>> m(matrices.size());
  for (size_t i = 0; i < matrices.size(); ++i)
    m[i] = matrices[i].matrix().topRows<3>().cast<float>();
  for (size_t v = 0; v < n; ++v) {
    const VertexBones& vb = mesh.bones[v];
    Eigen::Matrix<float, 3, 4> blend = Eigen::Matrix<float, 3, 4>::Zero();
    bool any = false;
    for (int k = 0; k < 4; ++k) {
      if (vb.bone[k] < 0 || vb.weight[k] <= 0) continue;
      blend += vb.weight[k] * m[vb.bone[k]];
      any = true;
    }
    if (!any) {
      positions[v] = mesh.positions[v];
      if (has_normals) normals[v] = mesh.normals[v];
      continue;
    }
    positions[v] = blend.leftCols<3>() * mesh.positions[v] + blend.col(3);
    if (!has_normals) continue;
    // The blended linear part is a rotation times a near-uniform scale for
    // these rigs: transforming the normal by it and renormalising is enough.
    const Eigen::Vector3f nrm = blend.leftCols<3>() * mesh.normals[v];
    const float len = nrm.norm();
    normals[v] = len > 1e-12f ? Eigen::Vector3f(nrm / len) : mesh.normals[v];
  }
}

}  // namespace depot::sim::testing
