// The shipped a-priori table for COCO detectors and the scoring's class
// mapping agree on the pig, which COCO has no label for: every label that
// counts as finding a pig must make its keypoints dynamic, or a pig the
// detector found would still be tracked.
#include <fstream>

#include <gtest/gtest.h>

#include "eval/class_mapping.h"
#include "slam/reject/apriori_classes.h"

namespace depot {
namespace {

const std::string kSource = DEPOT_SOURCE_DIR;

TEST(AprioriTables, EveryCocoLabelThatFindsAPigIsDynamic) {
  const auto mapping = eval::ClassMapping::load(kSource + "/scenes/detectors/coco_to_depot.yaml");
  const auto apriori = slam::AprioriClasses::load(kSource + "/scenes/apriori/coco.yaml");
  std::ifstream names(std::string(DEPOT_SHARED_DATA) + "/models/yolo-fastest-1.1/coco.names");
  ASSERT_TRUE(names) << "coco.names missing from the shared data";
  int pig_labels = 0;
  for (std::string label; std::getline(names, label);) {
    if (label.empty() || !mapping.matches(label, "pig")) continue;
    ++pig_labels;
    EXPECT_EQ(apriori.classify(label), slam::MotionClass::kDynamic)
        << "'" << label << "' finds a pig but is not dynamic in scenes/apriori/coco.yaml";
  }
  EXPECT_GE(pig_labels, 6) << "sheep, cow, horse, dog, cat, bird at least";
}

}  // namespace
}  // namespace depot
