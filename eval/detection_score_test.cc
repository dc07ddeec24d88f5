// Detector scoring with hand-made boxes: IoU matching, greedy by confidence,
// class mapping (pig as any animal), buckets, the clearly visible rule,
// precision and the confusion matrix.
#include "eval/detection_score.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "eval/box_matching.h"
#include "eval/class_mapping.h"
#include "eval/test_files.h"

namespace depot::eval {
namespace {

TruthObject truth(const std::string& cls, float x, float y, float w, float h, double visible = -1,
                  const std::string& model = "") {
  return {cls, cv::Rect2f(x, y, w, h), visible < 0 ? static_cast<double>(w * h) : visible, model};
}

ScoredDetection det(const std::string& label, float conf, float x, float y, float w, float h) {
  return {label, conf, cv::Rect2f(x, y, w, h)};
}

using testing::write_test_file;

ClassMapping coco_mapping() {
  return ClassMapping::load(std::string(DEPOT_SOURCE_DIR) + "/scenes/detectors/coco_to_depot.yaml");
}

// The simulator's detectable classes (a dataset's classes.txt).
const std::vector<std::string> kDepot{"person", "dog",  "cat",  "pig",    "bird",
                                      "chair",  "cart", "desk", "monitor"};

TEST(BoxMatching, IntersectionOverUnion) {
  EXPECT_DOUBLE_EQ(box_iou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.0);
  EXPECT_DOUBLE_EQ(box_iou({0, 0, 10, 10}, {5, 0, 10, 10}), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(box_iou({0, 0, 10, 10}, {20, 20, 5, 5}), 0.0);
  EXPECT_DOUBLE_EQ(box_iou({0, 0, 0, 0}, {0, 0, 0, 0}), 0.0);
}

TEST(BoxMatching, GreedyByConfidenceNotByOverlap) {
  // Both detections overlap the one box; the confident one takes it even
  // though the other overlaps more; the other is left unmatched.
  const std::vector<TruthObject> t{truth("person", 0, 0, 100, 100)};
  const std::vector<ScoredDetection> d{det("person", 0.4f, 0, 0, 100, 100),
                                       det("person", 0.9f, 10, 10, 100, 100)};
  Matching m = no_matches(t.size(), d.size());
  greedy_match(
      t, d, 0.5, [](size_t, size_t) { return true; }, m);
  EXPECT_EQ(m.detection_of_truth[0], 1);
  EXPECT_EQ(m.truth_of_detection[0], -1);
}

TEST(BoxMatching, EachDetectionTakesItsBestFreeBoxAboveTheThreshold) {
  const std::vector<TruthObject> t{truth("a", 0, 0, 100, 100), truth("a", 30, 0, 100, 100)};
  const std::vector<ScoredDetection> d{det("a", 0.9f, 28, 0, 100, 100),
                                       det("a", 0.8f, 2, 0, 100, 100),
                                       det("a", 0.7f, 500, 0, 10, 10)};
  Matching m = no_matches(t.size(), d.size());
  greedy_match(
      t, d, 0.5, [](size_t, size_t) { return true; }, m);
  EXPECT_EQ(m.truth_of_detection, (std::vector<int>{1, 0, -1}));
  // IoU 0.5 exactly counts; just below does not.
  const std::vector<TruthObject> one{truth("a", 0, 0, 30, 10)};
  Matching half = no_matches(1, 1);
  greedy_match(
      one, {det("a", 1, 10, 0, 30, 10)}, 0.5, [](size_t, size_t) { return true; }, half);
  EXPECT_EQ(half.detection_of_truth[0], 0) << "IoU 20/40 = 0.5";
  Matching less = no_matches(1, 1);
  greedy_match(
      one, {det("a", 1, 10.5f, 0, 30, 10)}, 0.5, [](size_t, size_t) { return true; }, less);
  EXPECT_EQ(less.detection_of_truth[0], -1);
}

TEST(DetectionScore, RecallAndPrecisionPerClassAfterMapping) {
  DetectionScore s(kDepot, coco_mapping());
  s.add_frame({truth("person", 0, 0, 100, 200), truth("desk", 200, 200, 200, 100),
               truth("dog", 400, 0, 80, 60)},
              {det("person", 0.9f, 2, 2, 100, 200), det("diningtable", 0.6f, 205, 200, 200, 100),
               det("cat", 0.5f, 400, 0, 80, 60), det("person", 0.4f, 600, 400, 30, 60)});
  EXPECT_EQ(s.tally("person").all.found, 1);
  EXPECT_EQ(s.tally("desk").all.found, 1) << "diningtable counts as desk";
  EXPECT_EQ(s.tally("dog").all.found, 0) << "a cat is not a dog";
  EXPECT_EQ(s.tally("person").precision.found, 1);
  EXPECT_EQ(s.tally("person").precision.total, 2);
  EXPECT_EQ(s.tally("cat").precision.total, 1);
  EXPECT_EQ(s.tally("cat").precision.found, 0);
  EXPECT_EQ(s.false_positives(), 2);
  EXPECT_DOUBLE_EQ(s.false_positives_per_frame(), 2.0);
  EXPECT_NEAR(s.tally("person").iou_sum, box_iou({0, 0, 100, 200}, {2, 2, 100, 200}), 1e-9);
}

TEST(DetectionScore, PigIsMatchedByAnyAnimalLabel) {
  DetectionScore s(kDepot, coco_mapping());
  s.add_frame({truth("pig", 0, 0, 100, 100), truth("pig", 200, 0, 100, 100),
               truth("pig", 400, 0, 100, 100)},
              {det("sheep", 0.8f, 0, 0, 100, 100), det("dog", 0.7f, 200, 0, 100, 100),
               det("umbrella", 0.6f, 400, 0, 100, 100)});
  EXPECT_EQ(s.tally("pig").all.found, 2);
  EXPECT_EQ(s.tally("pig").all.total, 3);
  // The confusion shows what it was called; the umbrella is a confusion
  // (class-blind match), and not a scored detection.
  EXPECT_EQ(s.confusion(false).at("pig").at("sheep"), 1);
  EXPECT_EQ(s.confusion(false).at("pig").at("dog"), 1);
  EXPECT_EQ(s.confusion(false).at("pig").at("umbrella"), 1);
  EXPECT_EQ(s.other_detections(), 1);
  EXPECT_EQ(s.tally("sheep").precision.found, 1) << "a sheep on a pig is correct";
  EXPECT_EQ(s.false_positives(), 0);
}

TEST(DetectionScore, IdentityMappingComparesNames) {
  DetectionScore s({"person", "pig"}, ClassMapping());
  s.add_frame({truth("pig", 0, 0, 100, 100)}, {det("sheep", 0.8f, 0, 0, 100, 100)});
  EXPECT_EQ(s.tally("pig").all.found, 0);
  EXPECT_EQ(s.other_detections(), 1);
}

TEST(DetectionScore, ClearlyVisibleBoxesAndBuckets) {
  DetectionScore s({"person"}, ClassMapping());
  // 100 px tall with 4000 visible pixels is clear; 99 px or 3999 px is not.
  s.add_frame({truth("person", 0, 0, 50, 100, 4000), truth("person", 100, 0, 50, 99, 4000),
               truth("person", 200, 0, 50, 100, 3999), truth("person", 300, 0, 20, 40, 100)},
              {det("person", 0.9f, 0, 0, 50, 100), det("person", 0.9f, 300, 0, 20, 40)});
  const ClassTally& t = s.tally("person");
  EXPECT_EQ(t.clear.total, 1);
  EXPECT_EQ(t.clear.found, 1);
  EXPECT_EQ(t.all.total, 4);
  EXPECT_EQ(t.all.found, 2);
  // Heights 100, 99, 100, 40: buckets <50, 50-100, 100-200, >=200.
  EXPECT_EQ(t.by_height[0].total, 1);
  EXPECT_EQ(t.by_height[0].found, 1);
  EXPECT_EQ(t.by_height[1].total, 1);
  EXPECT_EQ(t.by_height[2].total, 2);
  EXPECT_EQ(t.by_height[2].found, 1);
  EXPECT_EQ(t.by_height[3].total, 0);
  EXPECT_TRUE(std::isnan(t.by_height[3].rate()));
  // Visible fractions 0.8, 0.81, 0.8, 0.125: buckets >=0.75 and <0.25.
  EXPECT_EQ(t.by_fill[3].total, 3);
  EXPECT_EQ(t.by_fill[0].total, 1);
  EXPECT_EQ(s.rules().height_bucket_names(),
            (std::vector<std::string>{"<50", "50-100", "100-200", ">=200"}));
  EXPECT_EQ(s.rules().fill_bucket_names(),
            (std::vector<std::string>{"<0.25", "0.25-0.5", "0.5-0.75", ">=0.75"}));
}

TEST(DetectionScore, ConfusionPrefersTheRightClassThenAnyClassThenMissed) {
  DetectionScore s(kDepot, coco_mapping());
  // Box 1 is detected as person and (more confidently) as chair: it counts
  // as found, on the diagonal. Box 2 only as chair: confusion. Box 3: missed.
  s.add_frame({truth("person", 0, 0, 100, 200), truth("person", 200, 0, 100, 200),
               truth("person", 400, 0, 100, 200)},
              {det("chair", 0.9f, 0, 0, 100, 200), det("person", 0.5f, 0, 0, 100, 200),
               det("chair", 0.8f, 200, 0, 100, 200)});
  const auto& row = s.confusion(true).at("person");
  EXPECT_EQ(row.at("person"), 1);
  EXPECT_EQ(row.at("chair"), 1);
  EXPECT_EQ(row.at(DetectionScore::kMissed), 1);
  EXPECT_EQ(s.tally("person").all.found, 1);
  EXPECT_EQ(s.tally("chair").precision.total, 2);
  EXPECT_EQ(s.tally("chair").precision.found, 0);
  EXPECT_EQ(s.false_positives(), 2);
}

TEST(ClassMapping, ReadsMapAndAnyAnimal) {
  const ClassMapping m = coco_mapping();
  EXPECT_EQ(m.class_of("diningtable"), "desk");
  EXPECT_EQ(m.class_of("tvmonitor"), "monitor");
  EXPECT_EQ(m.class_of("sheep"), "sheep") << "unlisted labels count as themselves";
  EXPECT_TRUE(m.matches("cow", "pig"));
  EXPECT_FALSE(m.matches("cow", "dog"));
  EXPECT_TRUE(m.reachable("pig", {"person", "sheep"}));
  EXPECT_FALSE(m.reachable("cart", {"person", "sheep"}));
  EXPECT_TRUE(m.relevant("horse", kDepot)) << "could be a pig";
  EXPECT_FALSE(m.relevant("umbrella", kDepot));
  EXPECT_NO_THROW(m.check_classes(kDepot, "the dataset"));
}

TEST(ClassMapping, BadFilesNameFileAndLine) {
  const std::string unknown_class =
      write_test_file("typo.yaml", "map:\n  person: person\n  dog: dgo\n");
  EXPECT_EQ(
      error_of([&] { ClassMapping::load(unknown_class).check_classes(kDepot, "classes.txt"); }),
      unknown_class +
          ":3: class 'dgo' is not a class of classes.txt (person, dog, cat, pig, bird, "
          "chair, cart, desk, monitor)");
  const std::string animal =
      write_test_file("animal.yaml", "any_animal:\n  classes: [pgi]\n  labels: [dog]\n");
  EXPECT_EQ(error_of([&] {
              ClassMapping::load(animal).check_classes(kDepot, "x");
            }).rfind(animal + ":2: class 'pgi' is not a class of x", 0),
            0u);
  const std::string key = write_test_file("key.yaml", "mapping:\n  person: person\n");
  EXPECT_EQ(error_of([&] { ClassMapping::load(key); }),
            key + ":1: unknown key 'mapping' (expected map, any_animal)");
  const std::string list = write_test_file("list.yaml", "map:\n  person: [person]\n");
  EXPECT_EQ(error_of([&] { ClassMapping::load(list); }),
            list + ":2: a mapped class must be a class name");
  const std::string half = write_test_file("half.yaml", "any_animal:\n  classes: [pig]\n");
  EXPECT_EQ(error_of([&] { ClassMapping::load(half); }),
            half + ":2: 'any_animal' needs both 'classes' and 'labels'");
  const std::string broken = write_test_file("broken.yaml", "map: {person: person\n");
  EXPECT_NE(error_of([&] { ClassMapping::load(broken); }).find("YAML syntax error"),
            std::string::npos);
}

TEST(DetectionScore, RecallPerCatalogueModel) {
  DetectionScore s({"person", "dog"}, ClassMapping{});
  // Two people models, one found twice, one missed; the dog has no model.
  s.add_frame(
      {truth("person", 0, 0, 100, 200, -1, "worker_male"),
       truth("person", 300, 0, 100, 200, -1, "female_casual"), truth("dog", 500, 300, 100, 100)},
      {det("person", 0.9f, 0, 0, 100, 200)});
  s.add_frame({truth("person", 0, 0, 100, 200, -1, "worker_male")},
              {det("person", 0.9f, 2, 0, 100, 200)});
  const auto& m = s.by_model();
  ASSERT_EQ(m.count("person"), 1u);
  EXPECT_EQ(m.count("dog"), 0u) << "boxes without a model are not listed";
  EXPECT_EQ(m.at("person").at("worker_male").all.found, 2);
  EXPECT_EQ(m.at("person").at("worker_male").clear.total, 2);
  EXPECT_EQ(m.at("person").at("female_casual").all.found, 0);
  EXPECT_EQ(m.at("person").at("female_casual").all.total, 1);
}

}  // namespace
}  // namespace depot::eval
