#pragma once
// Ground truth of which pixels lie on moving objects, from a simulated
// dataset's instance labels (labels.txt, labels/) and per-frame moving flags
// (object_poses.txt). Used to score dynamic-feature rejection.
#include <map>
#include <set>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::eval {

class MotionTruth {
 public:
  // Throws depot::Error when the dataset has no labels (not simulated).
  explicit MotionTruth(const std::string& dataset);
  static bool available(const std::string& dataset);

  // For each keypoint of the frame with this rgb timestamp: 1 when its pixel
  // belongs to an object flagged moving in that frame.
  std::vector<uint8_t> on_moving_object(double timestamp,
                                        const std::vector<cv::KeyPoint>& keypoints) const;

  struct KeypointTruth {
    std::vector<uint8_t> on_moving;    // its centre pixel is on a moving object
    std::vector<uint8_t> near_moving;  // a pixel within the radius is
  };
  // Both labels from one read of the frame's label image. `near_radius`
  // (px, a disc): a keypoint there has its corner test (FAST's circle has
  // radius 3) see a moving object even if its centre pixel does not.
  KeypointTruth classify_keypoints(double timestamp, const std::vector<cv::KeyPoint>& keypoints,
                                   int near_radius) const;

  // Share of the frame's pixels on objects flagged moving (0..1): the
  // dynamic load a sweep reports alongside its knobs.
  double moving_fraction(double timestamp) const;

  // The rgb timestamps that have a label image, in increasing order.
  std::vector<double> timestamps() const;

  // The label image (CV_16U instance ids) of the frame with this rgb
  // timestamp. Throws depot::Error when it has none or it is unreadable.
  cv::Mat label_image(double timestamp) const;

 private:
  cv::Mat load_labels(const std::string& key) const;

  std::string root_;
  std::map<std::string, std::string> label_files_;   // stamp -> labels/x.png
  std::map<std::string, std::set<int>> moving_ids_;  // stamp -> ids moving
};

// Precision / recall of rejection, counting keypoints: rejected = predicted
// dynamic, on a moving object = truly dynamic.
struct RejectionScore {
  long true_positive = 0;   // rejected and moving
  long false_positive = 0;  // rejected but static (static points thrown away)
  long false_negative = 0;  // kept but moving
  long true_negative = 0;
  void add(const std::vector<uint8_t>& keep, const std::vector<uint8_t>& moving);
  // NaN when undefined (nothing rejected / nothing moving).
  double precision() const;
  double recall() const;
  long static_points() const { return false_positive + true_negative; }
};

}  // namespace depot::eval
