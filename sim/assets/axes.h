#pragma once
// Signed coordinate axes, as model files and the asset catalogue name them
// ("+y", "-z"), and the rotation that turns a file's axes into the model
// frame (z up, x forward).
#include <string>

#include <Eigen/Geometry>

namespace depot::sim {

enum class Axis { kPosX, kNegX, kPosY, kNegY, kPosZ, kNegZ };

// "+x", "-x", "+y", "-y", "+z", "-z" (also "x" for "+x"); fails naming
// `where` for anything else.
Axis parse_axis(const std::string& text, const std::string& where);
const char* axis_name(Axis axis);
Eigen::Vector3d axis_vector(Axis axis);

// The rotation taking the file's `up` to +z and `forward` (the way the model
// faces) to +x, so up x forward (the model's left) becomes +y. Fails naming
// `where` when the two axes are not perpendicular.
Eigen::Matrix3d model_rotation(Axis up, Axis forward, const std::string& where);

}  // namespace depot::sim
