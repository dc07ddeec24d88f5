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

  // The boundary rule: a FAST corner whose centre pixel is background but
  // whose test circle (the 16 pixels at radius 3 of FAST-9, at the
  // keypoint's pyramid level: radius 3 * scale_factor^octave in image
  // pixels) touches a moving object is made by the mover's outline and
  // moves with it. It is on neither the mover nor the static world, and is
  // scored as its own class ("boundary"; see RejectionScore).
  struct KeypointTruth {
    std::vector<uint8_t> on_moving;  // its centre pixel is on a moving object
    std::vector<uint8_t> boundary;   // not on_moving, but its circle touches a mover
    std::vector<uint16_t> instance;  // the instance label at its centre (objects.json id)
  };
  // Both labels from one read of the frame's label image; `scale_factor` is
  // the ORB pyramid's (1.2 in ORB-SLAM2).
  KeypointTruth classify_keypoints(double timestamp, const std::vector<cv::KeyPoint>& keypoints,
                                   float scale_factor) const;

  // The frame's pixels on objects flagged moving in it (CV_8U, 255 =
  // moving), e.g. to leave them out of a dense map; `labels` (optional)
  // receives the label image it was made from (one read for both).
  cv::Mat moving_mask(double timestamp, cv::Mat* labels = nullptr) const;

  // Share of the frame's pixels on objects flagged moving (0..1): the
  // dynamic load a sweep reports alongside its knobs.
  double moving_fraction(double timestamp) const;

  // The rgb timestamps that have a label image, in increasing order.
  std::vector<double> timestamps() const;

  // The dataset folder.
  const std::string& root() const { return root_; }

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
// dynamic, on a moving object = truly dynamic. Boundary keypoints (see
// KeypointTruth) are never on a mover, so recall is the same whether they
// count as static or are left out; precision is reported both ways:
// precision() counts them as static (rejecting one is a false positive),
// precision_without_boundary() leaves them out.
struct RejectionScore {
  long true_positive = 0;   // rejected and moving
  long false_positive = 0;  // rejected but static (static points thrown away)
  long false_negative = 0;  // kept but moving
  long true_negative = 0;
  long boundary_false_positive = 0;  // of false_positive: boundary points
  long boundary_true_negative = 0;   // of true_negative: boundary points
  // `boundary` may be empty (no boundary class known).
  void add(const std::vector<uint8_t>& keep, const std::vector<uint8_t>& moving,
           const std::vector<uint8_t>& boundary = {});
  void add(const RejectionScore& other);
  // NaN when undefined (nothing rejected / nothing moving).
  double precision() const;
  double precision_without_boundary() const;
  double recall() const;
  long static_points() const { return false_positive + true_negative; }
  long boundary_points() const { return boundary_false_positive + boundary_true_negative; }
};

}  // namespace depot::eval
