#include "tests/support/dataset_reader.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "dataset/calibration.h"
#include "dataset/dataset_files.h"
#include "dataset/label_images.h"
#include "dataset/object_poses.h"

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
  return dataset::read_label_image(root, labels.at(i).path);
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
  d.calibration = dataset::read_calibration(root + "/calibration.yaml");
  d.frames = read_associations(root + "/associations.txt");
  d.groundtruth = read_tum_trajectory(root + "/groundtruth.txt");
  d.labels = dataset::read_label_list(root);
  for (const dataset::ObjectRecord& o : dataset::read_objects(root).objects) d.objects[o.id] = o;
  std::map<std::string, size_t> frame_of;
  for (size_t i = 0; i < d.frames.size(); ++i)
    frame_of[dataset::format_timestamp(d.frames[i].rgb_timestamp)] = i;
  d.object_poses.resize(d.frames.size());
  for (const dataset::ObjectPoseRecord& r : dataset::read_object_poses(root))
    d.object_poses.at(frame_of.at(dataset::format_timestamp(r.timestamp)))[r.id] = {r.pose,
                                                                                    r.moving};
  return d;
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
