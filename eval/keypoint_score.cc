#include "eval/keypoint_score.h"

#include <filesystem>
#include <map>

#include "common/error.h"
#include "dataset/dataset_files.h"
#include "dataset/objects.h"

namespace depot::eval {

RejectionScore score_frame(const MotionTruth& truth, double timestamp,
                           const std::vector<cv::KeyPoint>& keypoints,
                           const std::vector<uint8_t>& keep, float scale_factor,
                           MotionTruth::KeypointTruth* labels) {
  MotionTruth::KeypointTruth classified =
      truth.classify_keypoints(timestamp, keypoints, scale_factor);
  RejectionScore score;
  score.add(keep, classified.on_moving, classified.boundary);
  if (labels) *labels = std::move(classified);
  return score;
}

KeypointFileScore score_keypoint_file(const MotionTruth& truth, const KeypointFile& file,
                                      float scale_factor) {
  struct Frame {
    std::vector<cv::KeyPoint> keypoints;
    std::vector<uint8_t> keep;
  };
  std::map<double, Frame> frames;
  for (const KeypointRow& row : file.rows) {
    Frame& f = frames[row.timestamp];
    cv::KeyPoint k(row.x, row.y, 7.0f, -1.0f, static_cast<float>(row.response), row.octave);
    f.keypoints.push_back(k);
    f.keep.push_back(row.kept ? 1 : 0);
  }
  KeypointFileScore out;
  std::map<int, std::string> class_of;
  if (std::filesystem::is_regular_file(std::filesystem::path(truth.root()) / dataset::kObjectsFile))
    for (const auto& o : dataset::read_objects(truth.root()).objects) class_of[o.id] = o.class_name;
  for (const auto& [t, f] : frames) {
    MotionTruth::KeypointTruth labels;
    out.score.add(score_frame(truth, t, f.keypoints, f.keep, scale_factor, &labels));
    out.keypoints += f.keypoints.size();
    for (size_t i = 0; i < f.keypoints.size(); ++i) {
      if (!labels.on_moving[i]) continue;
      const auto it = class_of.find(labels.instance[i]);
      if (it == class_of.end()) continue;
      ClassRecall& c = out.moving_by_class[it->second];
      ++c.moving;
      c.rejected += f.keep[i] ? 0 : 1;
    }
  }
  out.frames = frames.size();
  return out;
}

KeypointFileScore score_dataset_keypoints(const std::string& dataset,
                                          const std::string& keypoints_path, float scale_factor) {
  const MotionTruth truth(dataset);  // one error line when it has no labels
  KeypointFrames frames;
  frames.dataset = dataset;
  frames.timestamps = truth.timestamps();
  if (frames.timestamps.empty()) fail(dataset, "labels.txt lists no frames");
  frames.image = truth.label_image(frames.timestamps.front()).size();
  const KeypointFile file = read_keypoint_file(keypoints_path, frames);
  KeypointFileScore out = score_keypoint_file(truth, file, scale_factor);
  out.dataset_frames = frames.timestamps.size();
  out.has_octave = file.has_octave;
  return out;
}

}  // namespace depot::eval
