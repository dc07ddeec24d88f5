#pragma once
// Test oracle: linear blend skinning of a posed model on the CPU, what MuJoCo
// does to a `<skin>` when it renders (the simulator's real path:
// sim/assets/skinning.h). Tests compare MuJoCo's skinned vertices and the
// poses' effect on the meshes against it.
#include <vector>

#include "sim/assets/asset_model.h"

namespace depot::sim::testing {

// The skinning matrix of every bone: global * inverse_bind (identity at the
// bind pose).
void skinning_matrices(const Skeleton& skeleton, const std::vector<Eigen::Affine3d>& globals,
                       std::vector<Eigen::Affine3d>& matrices);

// Linear blend skinning of one mesh: deformed positions and unit normals in
// the model frame (no normals out for a mesh without normals). A rigid mesh
// (no bone weights) and unweighted vertices keep their bind positions.
void skin_mesh(const AssetMesh& mesh, const std::vector<Eigen::Affine3d>& matrices,
               std::vector<Eigen::Vector3f>& positions, std::vector<Eigen::Vector3f>& normals);

}  // namespace depot::sim::testing
