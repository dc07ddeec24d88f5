#pragma once
// A SLAM system under test that is another program, described by a YAML
// file (scenes/systems/ holds the shipped ones):
//
//   description: Open3D's frame-to-frame RGB-D odometry   (optional)
//   command: [/usr/bin/python3, "{system_dir}/open3d_odometry.py",
//             "{dataset}", "{intrinsics}", "{trajectory}"]
//   trajectory_format: tum     # tum | kitti | euroc (as evo reads them)
//   time_limit_s: 600          # optional, default 3600
//   env: {OMP_NUM_THREADS: "1"}                             (optional)
//
// The command is argv, run without a shell. Placeholders ("{name}", name in
// lower-case letters and '_'; other braces are text), replaced inside every
// argument:
//   {dataset}           the TUM RGB-D folder
//   {calibration}       its calibration.yaml (this project's format)
//   {orbslam_settings}  an ORB-SLAM2-style settings YAML written for it
//   {intrinsics}        a text file with one line "fx fy cx cy"
//   {depth_factor}      depth PNG value per metre (e.g. 5000)
//   {trajectory}        where the system writes its trajectory
//   {keypoints}         where it may write its per-keypoint decisions
//                       (eval/keypoint_file.h); naming it promises the file
//   {timestamps}        where a KITTI system writes its poses' timestamps
//                       (seconds, one a line, as KITTI's times.txt)
//   {work}              a scratch folder for the run
//   {system_dir}        the folder of the system file
//   {depot}             this depot program (to wrap a built-in mode)
// A KITTI trajectory without {timestamps} has one pose per frame of the
// dataset, in order.
#include <map>
#include <string>
#include <vector>

namespace depot::system {

enum class TrajectoryFormat { kTum, kKitti, kEuroc };

struct SystemSpec {
  std::string name;  // the file's stem
  std::string path;  // the file
  std::string description;
  std::vector<std::string> command;
  TrajectoryFormat trajectory_format = TrajectoryFormat::kTum;
  double time_limit_s = 3600;
  std::map<std::string, std::string> env;
  bool writes_keypoints = false;   // the command names {keypoints}
  bool writes_timestamps = false;  // the command names {timestamps} (KITTI)
};

// Every placeholder a command may use.
const std::vector<std::string>& system_placeholders();

// Throws depot::Error("<path>[:<line>]: <problem>") for a missing file, bad
// YAML, an unknown key, an empty command, an unknown placeholder, an
// unknown trajectory format, a time limit outside
// (0, 86400] s, or a command that never names {trajectory}.
SystemSpec load_system_spec(const std::string& path);

// A system named in a sweep's modes ("system:NAME") or given to --system:
// a path to a YAML file (it contains '/' or ends in .yaml), else the shipped
// scenes/systems/NAME.yaml. Throws depot::Error when there is no such file.
std::string find_system_file(const std::string& name);

// The argv with every placeholder replaced by its value in `values`.
std::vector<std::string> expand_command(const SystemSpec& spec,
                                        const std::map<std::string, std::string>& values);

const char* trajectory_format_name(TrajectoryFormat format);

// Sweeps and regression bounds name a system as a mode: "system:NAME".
inline constexpr const char* kSystemModePrefix = "system:";
bool is_system_mode(const std::string& mode);
// NAME of "system:NAME" ("" for a built-in mode).
std::string system_of_mode(const std::string& mode);

}  // namespace depot::system
