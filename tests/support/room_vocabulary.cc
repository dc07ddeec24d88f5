#include "tests/support/room_vocabulary.h"

#include <vector>

#include <opencv2/imgproc.hpp>

#include "common/testing/temp_path.h"
#include "slam/feature/orb_extractor.h"
#include "slam/place/vocabulary_file.h"
#include "slam/place/vocabulary_training.h"
#include "tests/support/synthetic_room.h"

namespace depot::test {

std::shared_ptr<const slam::Vocabulary> room_vocabulary() {
  static const std::shared_ptr<const slam::Vocabulary> vocabulary = [] {
    SyntheticRoom room;
    room.seed = 2;
    const slam::PinholeCamera camera;
    slam::OrbExtractor extractor{slam::OrbParams{}};
    std::vector<cv::Mat> descriptors;
    // Views from the centre and from beside it, turned every 45 degrees.
    for (int k = 0; k < 8; ++k)
      for (const double x : {0.0, 0.8}) {
        Pose T_wc = Pose::Identity();
        T_wc.linear() = turn(45.0 * k, k % 2 ? 10.0 : -10.0);
        T_wc.translation() = Eigen::Vector3d(x, 0.2, -x);
        const RealFrame view = render_room(room, camera, T_wc.inverse());
        cv::Mat gray, d;
        cv::cvtColor(view.bgr, gray, cv::COLOR_BGR2GRAY);
        std::vector<cv::KeyPoint> keypoints;
        extractor.extract(gray, cv::Mat(), keypoints, d);
        descriptors.push_back(d);
      }
    return std::make_shared<const slam::Vocabulary>(
        slam::train_vocabulary(descriptors, slam::VocabularyTrainingParams{6, 4, 10, 1}));
  }();
  return vocabulary;
}

const std::string& room_vocabulary_file() {
  static const std::string path = [] {
    const std::string p = testkit::temp_path("room_vocabulary") + ".voc";
    slam::save_vocabulary(*room_vocabulary(), p);
    return p;
  }();
  return path;
}

}  // namespace depot::test
