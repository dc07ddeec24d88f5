#include "sim/assets/axes.h"

#include "common/error.h"

namespace depot::sim {

Axis parse_axis(const std::string& text, const std::string& where) {
  if (text == "+x" || text == "x") return Axis::kPosX;
  if (text == "-x") return Axis::kNegX;
  if (text == "+y" || text == "y") return Axis::kPosY;
  if (text == "-y") return Axis::kNegY;
  if (text == "+z" || text == "z") return Axis::kPosZ;
  if (text == "-z") return Axis::kNegZ;
  fail(where, "unknown axis '" + text + "' (expected +x, -x, +y, -y, +z or -z)");
}

const char* axis_name(Axis axis) {
  switch (axis) {
    case Axis::kPosX:
      return "+x";
    case Axis::kNegX:
      return "-x";
    case Axis::kPosY:
      return "+y";
    case Axis::kNegY:
      return "-y";
    case Axis::kPosZ:
      return "+z";
    case Axis::kNegZ:
      return "-z";
  }
  return "+x";
}

Eigen::Vector3d axis_vector(Axis axis) {
  switch (axis) {
    case Axis::kPosX:
      return Eigen::Vector3d::UnitX();
    case Axis::kNegX:
      return -Eigen::Vector3d::UnitX();
    case Axis::kPosY:
      return Eigen::Vector3d::UnitY();
    case Axis::kNegY:
      return -Eigen::Vector3d::UnitY();
    case Axis::kPosZ:
      return Eigen::Vector3d::UnitZ();
    case Axis::kNegZ:
      return -Eigen::Vector3d::UnitZ();
  }
  return Eigen::Vector3d::UnitX();
}

Eigen::Matrix3d model_rotation(Axis up, Axis forward, const std::string& where) {
  const Eigen::Vector3d u = axis_vector(up), f = axis_vector(forward);
  if (std::abs(u.dot(f)) > 0.5)
    fail(where, std::string("up axis ") + axis_name(up) + " and forward axis " +
                    axis_name(forward) + " must be perpendicular");
  // Rows are the file's axes that become model x, y and z: R * f = x, R * u = z.
  Eigen::Matrix3d r;
  r.row(0) = f.transpose();
  r.row(1) = u.cross(f).transpose();
  r.row(2) = u.transpose();
  return r;
}

}  // namespace depot::sim
