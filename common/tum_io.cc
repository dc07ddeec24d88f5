#include "common/tum_io.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/staged_file.h"

namespace depot {
namespace {

// Splits the non-comment, non-empty lines of a text file into fields,
// remembering line numbers for error messages.
struct Row {
  int line = 0;
  std::vector<std::string> fields;
};

// `commas`: fields are separated by commas as well (CSV).
std::vector<Row> read_rows(const std::string& path, bool commas = false) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a folder, not a TUM text file");
  std::ifstream in(path);
  if (!in) fail(path, "cannot open file");
  std::vector<Row> rows;
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos || text[first] == '#') continue;
    // Some copies of TUM files carry the column header without '#'.
    if (rows.empty() && text.compare(first, 9, "timestamp") == 0) continue;
    Row row;
    row.line = line_no;
    if (commas)
      for (char& c : text)
        if (c == ',') c = ' ';
    std::istringstream fields(text);
    std::string f;
    while (fields >> f) row.fields.push_back(f);
    // Only whitespace (e.g. a vertical tab or form feed): a blank line.
    if (row.fields.empty()) continue;
    rows.push_back(std::move(row));
  }
  if (in.bad()) fail(path, "read error");
  return rows;
}

std::string where(const std::string& path, const Row& row) {
  return path + ":" + std::to_string(row.line);
}

double parse_number(const std::string& path, const Row& row, size_t i) {
  const std::string& s = row.fields[i];
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0') fail(where(path, row), "'" + s + "' is not a number");
  if (!std::isfinite(v)) fail(where(path, row), "value '" + s + "' is not finite");
  return v;
}

void require_fields(const std::string& path, const Row& row, size_t n, const char* format) {
  if (row.fields.size() < n) {
    fail(where(path, row), "expected " + std::to_string(n) + " fields (" + format + "), found " +
                               std::to_string(row.fields.size()));
  }
}

void require_increasing(const std::string& path, const Row& row, double prev, double t) {
  if (t <= prev) fail(where(path, row), "timestamps must increase");
}

}  // namespace

std::vector<StampedPose> read_tum_trajectory(const std::string& path) {
  std::vector<StampedPose> out;
  double prev = -INFINITY;
  for (const Row& row : read_rows(path)) {
    require_fields(path, row, 8, "timestamp tx ty tz qx qy qz qw");
    if (row.fields.size() > 8)
      fail(where(path, row), "expected 8 fields (timestamp tx ty tz qx qy qz qw), found " +
                                 std::to_string(row.fields.size()) +
                                 " (comments are lines starting with '#')");
    double v[8];
    for (size_t i = 0; i < 8; ++i) v[i] = parse_number(path, row, i);
    require_increasing(path, row, prev, v[0]);
    prev = v[0];
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
    if (!(std::abs(q.norm() - 1.0) <= kQuaternionNormTolerance)) {
      fail(where(path, row), "quaternion is not unit length (norm " +
                                 fmt::format("{:.6g}", q.norm()) + ", allowed 1 +- " +
                                 std::to_string(kQuaternionNormTolerance) + ")");
    }
    out.push_back({v[0], make_pose(q, Eigen::Vector3d(v[1], v[2], v[3]))});
  }
  if (out.empty()) fail(path, "no poses in trajectory file");
  return out;
}

std::vector<Pose> read_kitti_poses(const std::string& path) {
  std::vector<Pose> out;
  for (const Row& row : read_rows(path)) {
    if (row.fields.size() != 12)
      fail(where(path, row), "expected 12 fields (a 3x4 pose matrix, row by row), found " +
                                 std::to_string(row.fields.size()));
    double v[12];
    for (size_t i = 0; i < 12; ++i) v[i] = parse_number(path, row, i);
    Eigen::Matrix3d r;
    r << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
    const double error = (r.transpose() * r - Eigen::Matrix3d::Identity()).norm();
    if (!(error <= kRotationTolerance) || r.determinant() <= 0)
      fail(where(path, row), "the 3x3 part is not a rotation");
    // Re-orthonormalise what the file's rounding left.
    out.push_back(
        make_pose(Eigen::Quaterniond(r).normalized(), Eigen::Vector3d(v[3], v[7], v[11])));
  }
  if (out.empty()) fail(path, "no poses in trajectory file");
  return out;
}

std::vector<StampedPose> read_euroc_trajectory(const std::string& path) {
  std::vector<StampedPose> out;
  double prev = -INFINITY;
  for (const Row& row : read_rows(path, /*commas=*/true)) {
    require_fields(path, row, 8, "timestamp[ns], px, py, pz, qw, qx, qy, qz");
    double v[8];
    for (size_t i = 0; i < 8; ++i) v[i] = parse_number(path, row, i);
    const double t = v[0] * 1e-9;
    require_increasing(path, row, prev, t);
    prev = t;
    const Eigen::Quaterniond q(v[4], v[5], v[6], v[7]);
    if (!(std::abs(q.norm() - 1.0) <= kQuaternionNormTolerance))
      fail(where(path, row), "quaternion is not unit length");
    out.push_back({t, make_pose(q, Eigen::Vector3d(v[1], v[2], v[3]))});
  }
  if (out.empty()) fail(path, "no poses in trajectory file");
  return out;
}

std::string format_tum_pose(const StampedPose& p) {
  Eigen::Quaterniond q(p.pose.linear());
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;  // one canonical sign, for stable files
  const Eigen::Vector3d& t = p.pose.translation();
  return fmt::format("{:.6f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f} {:.9f}", p.timestamp, t.x(),
                     t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
}

void write_text_file_atomic(const std::string& path, const std::string& text) {
  StagedFile file(path);
  file.stream() << text;
  file.commit();
}

std::string format_tum_trajectory(const std::vector<StampedPose>& poses,
                                  const std::string& header) {
  std::string text;
  if (!header.empty()) text += "# " + header + "\n";
  text += "# timestamp tx ty tz qx qy qz qw\n";
  for (const auto& p : poses) text += format_tum_pose(p) + "\n";
  return text;
}

void write_tum_trajectory(const std::string& path, const std::vector<StampedPose>& poses,
                          const std::string& header) {
  write_text_file_atomic(path, format_tum_trajectory(poses, header));
}

std::vector<StampedFile> read_file_list(const std::string& path) {
  std::vector<StampedFile> out;
  double prev = -INFINITY;
  for (const Row& row : read_rows(path)) {
    require_fields(path, row, 2, "timestamp filename");
    double t = parse_number(path, row, 0);
    require_increasing(path, row, prev, t);
    prev = t;
    out.push_back({t, row.fields[1]});
  }
  if (out.empty()) fail(path, "no entries in file list");
  return out;
}

std::vector<Association> read_associations(const std::string& path) {
  std::vector<Association> out;
  double prev = -INFINITY;
  for (const Row& row : read_rows(path)) {
    require_fields(path, row, 4, "t_rgb rgb t_depth depth");
    Association a;
    a.rgb_timestamp = parse_number(path, row, 0);
    a.rgb_path = row.fields[1];
    a.depth_timestamp = parse_number(path, row, 2);
    a.depth_path = row.fields[3];
    require_increasing(path, row, prev, a.rgb_timestamp);
    prev = a.rgb_timestamp;
    out.push_back(std::move(a));
  }
  if (out.empty()) fail(path, "no entries in association file");
  return out;
}

TumFileKind detect_tum_file_kind(const std::string& path) {
  auto rows = read_rows(path);
  if (rows.empty()) fail(path, "empty file");
  const Row& row = rows.front();
  char* end = nullptr;
  const std::string& second = row.fields.size() > 1 ? row.fields[1] : "";
  std::strtod(second.c_str(), &end);
  const bool second_is_number = !second.empty() && *end == '\0';
  if (second_is_number) return TumFileKind::kTrajectory;
  return row.fields.size() >= 4 ? TumFileKind::kAssociation : TumFileKind::kFileList;
}

std::vector<double> read_timestamps(const std::string& path) {
  std::vector<double> out;
  double prev = -INFINITY;
  for (const Row& row : read_rows(path)) {
    double t = parse_number(path, row, 0);
    require_increasing(path, row, prev, t);
    prev = t;
    out.push_back(t);
  }
  if (out.empty()) fail(path, "no timestamps in file");
  return out;
}

}  // namespace depot
