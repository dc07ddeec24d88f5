#include "tests/support/dataset_reader.h"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"

namespace fs = std::filesystem;

namespace depot::test {

cv::Mat Dataset::depth_metres(size_t i) const {
  cv::Mat raw = cv::imread(root + "/" + frames.at(i).depth_path, cv::IMREAD_UNCHANGED);
  if (raw.type() != CV_16U) throw Error("depth not 16-bit: " + frames.at(i).depth_path);
  cv::Mat m;
  raw.convertTo(m, CV_32F, 1.0 / calibration.depth_factor);
  return m;
}

cv::Mat Dataset::labels_image(size_t i) const {
  cv::Mat raw = cv::imread(root + "/" + labels.at(i).path, cv::IMREAD_UNCHANGED);
  if (raw.type() != CV_16U) throw Error("labels not 16-bit: " + labels.at(i).path);
  return raw;
}

cv::Mat Dataset::rgb(size_t i) const {
  return cv::imread(root + "/" + frames.at(i).rgb_path, cv::IMREAD_COLOR);
}

const ObjectInfo& Dataset::object(const std::string& name) const {
  for (const auto& [id, o] : objects)
    if (o.name == name) return o;
  throw Error("no object named " + name);
}

Dataset read_dataset(const std::string& root) {
  Dataset d;
  d.root = root;
  YAML::Node calib = YAML::LoadFile(root + "/calibration.yaml");
  d.calibration.width = calib["camera"]["width"].as<int>();
  d.calibration.height = calib["camera"]["height"].as<int>();
  d.calibration.fx = calib["camera"]["fx"].as<double>();
  d.calibration.fy = calib["camera"]["fy"].as<double>();
  d.calibration.cx = calib["camera"]["cx"].as<double>();
  d.calibration.cy = calib["camera"]["cy"].as<double>();
  d.calibration.depth_factor = calib["depth"]["factor"].as<double>();
  d.frames = read_associations(root + "/associations.txt");
  d.groundtruth = read_tum_trajectory(root + "/groundtruth.txt");
  d.labels = read_file_list(root + "/labels.txt");

  std::ifstream objects_file(root + "/objects.json");
  nlohmann::json objects = nlohmann::json::parse(objects_file);
  auto pose_of = [](const nlohmann::json& j) {
    auto t = j["t"];
    auto q = j["q_xyzw"];
    return make_pose(Eigen::Quaterniond(q[3], q[0], q[1], q[2]), Eigen::Vector3d(t[0], t[1], t[2]));
  };
  for (const auto& o : objects["instances"]) {
    ObjectInfo info;
    info.id = o["id"];
    info.name = o["name"];
    info.class_name = o["class"];
    info.asset = o.value("asset", "");
    info.category = o["category"];
    info.kind = o["kind"];
    info.pose = pose_of(o["pose"]);
    auto mn = o["extent"]["min"];
    auto mx = o["extent"]["max"];
    info.extent = Eigen::AlignedBox3d(Eigen::Vector3d(mn[0], mn[1], mn[2]),
                                      Eigen::Vector3d(mx[0], mx[1], mx[2]));
    d.objects[info.id] = info;
  }

  std::map<std::string, size_t> frame_of;
  for (size_t i = 0; i < d.frames.size(); ++i) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.6f", d.frames[i].rgb_timestamp);
    frame_of[buf] = i;
  }
  d.object_poses.resize(d.frames.size());
  std::ifstream poses(root + "/object_poses.txt");
  std::string line;
  while (std::getline(poses, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::string stamp;
    int id, moving;
    double v[7];
    in >> stamp >> id >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> moving;
    ObjectPose p;
    p.pose =
        make_pose(Eigen::Quaterniond(v[6], v[3], v[4], v[5]), Eigen::Vector3d(v[0], v[1], v[2]));
    p.moving = moving != 0;
    d.object_poses.at(frame_of.at(stamp))[id] = p;
  }
  return d;
}

namespace {

fs::path& test_root_path() {
  static fs::path root;
  return root;
}

void remove_test_root() {
  std::error_code ec;
  fs::remove_all(test_root_path(), ec);
}

// One new folder per test process, made by mkdtemp so it can never be the
// leftover of an earlier process that had the same id, and removed when the
// process exits (set DEPOT_KEEP_TEST_FILES to keep it for a post-mortem) so
// test runs do not fill the temporary folder.
const fs::path& test_root() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::string pattern = (fs::temp_directory_path() / "depot_test_XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw std::runtime_error("cannot create a test folder like " + pattern);
    test_root_path() = pattern;
    if (!std::getenv("DEPOT_KEEP_TEST_FILES")) std::atexit(remove_test_root);
  });
  return test_root_path();
}

}  // namespace

std::string temp_path(const std::string& tag) {
  static std::atomic<int> counter{0};
  return (test_root() / (tag + "_" + std::to_string(counter++))).string();
}

std::string write_yaml(const std::string& tag, const std::string& text) {
  const std::string path = temp_path(tag) + ".yaml";
  std::ofstream(path) << text;
  return path;
}

int run_command(const std::string& command, std::string* output) {
  std::string full = command + " 2>&1";
  FILE* pipe = popen(full.c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf;
  std::string out;
  while (size_t n = fread(buf.data(), 1, buf.size(), pipe)) out.append(buf.data(), n);
  int status = pclose(pipe);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string compare_trees(const std::string& a, const std::string& b) {
  std::vector<std::string> files_a, files_b;
  for (const auto& e : fs::recursive_directory_iterator(a))
    if (e.is_regular_file()) files_a.push_back(fs::relative(e.path(), a).string());
  for (const auto& e : fs::recursive_directory_iterator(b))
    if (e.is_regular_file()) files_b.push_back(fs::relative(e.path(), b).string());
  std::sort(files_a.begin(), files_a.end());
  std::sort(files_b.begin(), files_b.end());
  if (files_a != files_b) return "different file lists";
  for (const auto& f : files_a) {
    std::ifstream fa(a + "/" + f, std::ios::binary), fb(b + "/" + f, std::ios::binary);
    std::string ca((std::istreambuf_iterator<char>(fa)), {}),
        cb((std::istreambuf_iterator<char>(fb)), {});
    if (ca != cb) return f;
  }
  return "";
}

}  // namespace depot::test
