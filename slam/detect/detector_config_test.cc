// Detector YAML files: the shipped ones, relative paths, and bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "common/error.h"
#include "slam/detect/detector_config.h"
#include "slam/detect/detector_factory.h"
#include "slam/detect/test_support.h"

namespace depot::slam {
namespace {

std::string error_of(const std::string& yaml_path) {
  try {
    load_detector_config(yaml_path);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::string canonical(const std::string& p) {
  return std::filesystem::weakly_canonical(p).string();
}

TEST(DetectorConfig, ShippedYoloFastest) {
  const std::string dir = test::source_dir() + "/scenes/detectors";
  const DetectorConfig c = load_detector_config(dir + "/yolo_fastest.yaml");
  EXPECT_EQ(c.type, "darknet");
  // ${DEPOT_SHARED_DATA} in the file is the shared data folder.
  EXPECT_EQ(c.model, test::yolo_fastest_dir() + "/yolo-fastest-1.1.weights");
  EXPECT_EQ(c.config, test::yolo_fastest_dir() + "/yolo-fastest-1.1.cfg");
  EXPECT_EQ(c.names, test::yolo_fastest_dir() + "/coco.names");
  EXPECT_EQ(c.input_width, 320);
  EXPECT_EQ(c.input_height, 320);
  EXPECT_FLOAT_EQ(c.confidence, 0.3f);
  EXPECT_FLOAT_EQ(c.nms, 0.45f);
  EXPECT_TRUE(c.classes.empty());
  if (test::have_shared_data()) {
    // Those paths reach the real files.
    EXPECT_EQ(canonical(c.model),
              canonical(test::yolo_fastest_dir() + "/yolo-fastest-1.1.weights"));
    EXPECT_TRUE(std::filesystem::exists(c.config));
    EXPECT_TRUE(std::filesystem::exists(c.names));
  }
}

TEST(DetectorConfig, ShippedFastestDet) {
  const std::string dir = test::source_dir() + "/scenes/detectors";
  const DetectorConfig c = load_detector_config(dir + "/fastestdet.yaml");
  EXPECT_EQ(c.type, "fastestdet");
  EXPECT_EQ(c.model, test::fastestdet_dir() + "/FastestDet.onnx");
  EXPECT_EQ(c.input_width, 352);
  EXPECT_EQ(c.input_height, 352);
  EXPECT_TRUE(c.config.empty());
  if (test::have_shared_data()) {
    EXPECT_TRUE(std::filesystem::exists(c.model));
  }
}

TEST(DetectorConfig, ShippedYolov5sExpectsTheUsersModelBesideIt) {
  const std::string dir = test::source_dir() + "/scenes/detectors";
  const DetectorConfig c = load_detector_config(dir + "/yolov5s.yaml");
  EXPECT_EQ(c.type, "yolov5");
  EXPECT_EQ(c.model, dir + "/yolov5s.onnx");
  EXPECT_EQ(c.input_width, 640);
  if (!std::filesystem::exists(c.model)) {
    try {
      make_dnn_detector(c);
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind(c.model + ": model file not found (no YOLOv5 model "
                                                      "ships with depot-slam: export one with",
                                            0),
                0u)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("export.py --weights yolov5s.pt --include onnx"),
                std::string::npos);
    }
  }
}

TEST(DetectorConfig, AbsolutePathsClassesAndDefaults) {
  test::TempDir dir;
  const std::string p = dir.write("d.yaml",
                                  "type: yolov5\n"
                                  "model: /opt/models/yolov5s.onnx\n"
                                  "names: sub/coco.names\n"
                                  "confidence: 0.25\n"
                                  "classes: [person, dog, dining table]\n");
  const DetectorConfig c = load_detector_config(p);
  EXPECT_EQ(c.model, "/opt/models/yolov5s.onnx");
  EXPECT_EQ(c.names, dir.file("sub/coco.names"));
  EXPECT_EQ(c.input_width, 0);  // the type's default
  EXPECT_FLOAT_EQ(c.confidence, 0.25f);
  EXPECT_FLOAT_EQ(c.nms, 0.45f);
  EXPECT_EQ(c.classes, (std::vector<std::string>{"person", "dog", "dining table"}));
}

TEST(DetectorConfig, ErrorsNameTheFile) {
  test::TempDir dir;
  struct Case {
    const char* yaml;
    const char* message_part;
  };
  const Case cases[] = {
      {"type: yolov7\nmodel: m.onnx\nnames: c.names\n", "unknown detector type 'yolov7'"},
      {"model: m.onnx\nnames: c.names\n", "missing 'type'"},
      {"type: yolov5\nnames: c.names\n", "missing 'model'"},
      {"type: yolov5\nmodel: m.onnx\n", "missing 'names'"},
      {"type: darknet\nmodel: m.weights\nnames: c.names\n", "missing 'config'"},
      {"type: yolov5\nmodel: m.onnx\nnames: c.names\nconfig: x.cfg\n", "darknet only"},
      {"type: yolov5\nmodel: m.onnx\nnames: c.names\nconfidence: 1.5\n", "'confidence'"},
      {"type: yolov5\nmodel: m.onnx\nnames: c.names\nnms: abc\n", "'nms'"},
      {"type: yolov5\nmodel: m.onnx\nnames: c.names\ninput_width: 320\n", "input_height"},
      {"type: yolov5\nmodel: m.onnx\nnames: c.names\nthreshold: 0.5\n", "unknown key 'threshold'"},
      {"type: yolov5\nmodel: m.onnx\nnames: c.names\nclasses: person\n", "'classes'"},
      {"type: [yolov5\n", "YAML syntax error"},
      {"- just\n- a list\n", "must be a YAML map"},
      // Found by fuzzing (tests/fuzz/fuzz_detector_config): a quoted value
      // with a newline made the error two lines.
      {"type: \"yolo\\nv7\"\nmodel: m.onnx\nnames: c.names\n", "unknown detector type 'yolo\\nv7'"},
  };
  int i = 0;
  for (const Case& c : cases) {
    const std::string path = dir.write("bad" + std::to_string(i++) + ".yaml", c.yaml);
    const std::string e = error_of(path);
    EXPECT_EQ(e.rfind(path, 0), 0u) << c.yaml << " -> " << e;
    EXPECT_THAT(e, ::testing::HasSubstr(c.message_part)) << c.yaml << " -> " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << c.yaml << " -> " << e;
  }
  const std::string missing = dir.file("missing.yaml");
  EXPECT_EQ(error_of(missing), missing + ": cannot open detector config");
}

}  // namespace
}  // namespace depot::slam
