#pragma once
// Reading and writing the TUM RGB-D text formats: trajectories
// ("timestamp tx ty tz qx qy qz qw", camera-to-world), image lists
// ("timestamp path") and associations ("t_rgb rgb t_depth depth").
// Every parse error names the file and line.
#include <string>
#include <vector>

#include "common/pose.h"

namespace depot {

struct StampedPose {
  double timestamp = 0.0;
  Pose pose = Pose::Identity();
};

struct StampedFile {
  double timestamp = 0.0;
  std::string path;  // relative to the dataset folder
};

struct Association {
  double rgb_timestamp = 0.0;
  std::string rgb_path;
  double depth_timestamp = 0.0;
  std::string depth_path;
};

// A trajectory line has exactly 8 fields; its quaternion's norm must be
// within this of 1 (files with four decimals stay below 0.0002), and is then
// normalised.
inline constexpr double kQuaternionNormTolerance = 1e-3;

std::vector<StampedPose> read_tum_trajectory(const std::string& path);
// Writes atomically (temp file + rename). Quaternions are normalised.
void write_tum_trajectory(const std::string& path, const std::vector<StampedPose>& poses,
                          const std::string& header = "");

// The other trajectory formats evo reads, for systems that write them:
// KITTI poses (12 numbers a line, the 3x4 camera-to-world matrix row by row,
// no timestamps: one pose per frame in order) and EuRoC CSV
// ("timestamp[ns],px,py,pz,qw,qx,qy,qz[,...]", further columns ignored;
// timestamps are returned in seconds). The rotation must be orthonormal
// within kRotationTolerance (Frobenius norm of R^T R - I).
inline constexpr double kRotationTolerance = 1e-3;
std::vector<Pose> read_kitti_poses(const std::string& path);
std::vector<StampedPose> read_euroc_trajectory(const std::string& path);

std::vector<StampedFile> read_file_list(const std::string& path);
std::vector<Association> read_associations(const std::string& path);

enum class TumFileKind { kTrajectory, kFileList, kAssociation };
// Tells the kind of a TUM text file from its first data line.
TumFileKind detect_tum_file_kind(const std::string& path);

// The first column of any TUM text file (image list, association, trajectory).
std::vector<double> read_timestamps(const std::string& path);

// Formats one trajectory line (no newline), as write_tum_trajectory does.
std::string format_tum_pose(const StampedPose& p);
// The whole text write_tum_trajectory writes (for writers that stage several
// files and commit them together).
std::string format_tum_trajectory(const std::vector<StampedPose>& poses,
                                  const std::string& header = "");

// Writes text to path atomically: all of it or nothing.
void write_text_file_atomic(const std::string& path, const std::string& text);

}  // namespace depot
