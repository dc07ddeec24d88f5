#include "dataset/objects.h"

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/test_folder.h"

namespace depot::dataset {
namespace {

ObjectsFile two_objects() {
  ObjectsFile f;
  f.scenario = "depot_static";
  ObjectRecord desk;
  desk.id = 1;
  desk.name = "desk_0";
  desk.class_name = "desk";
  desk.category = "static";
  desk.kind = "static";
  desk.yolo_class = -1;
  desk.pose = make_pose(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
                        Eigen::Vector3d(1.5, -2.25, 0));
  desk.extent = Eigen::AlignedBox3d(Eigen::Vector3d(-1, -0.5, 0), Eigen::Vector3d(1, 0.5, 0.75));
  ObjectRecord walker = desk;
  walker.id = 2;
  walker.name = "walker_0";
  walker.class_name = "person";
  walker.category = "dynamic";
  walker.kind = "actor";
  walker.yolo_class = 0;
  walker.asset = "people/walker_a";
  f.objects = {desk, walker};
  return f;
}

TEST(Objects, RoundTrip) {
  const std::string dir = testing::new_test_folder();
  const ObjectsFile want = two_objects();
  write_objects(dir, want);
  const ObjectsFile read = read_objects(dir);
  EXPECT_EQ(read.scenario, want.scenario);
  ASSERT_EQ(read.objects.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const ObjectRecord& r = read.objects[i];
    const ObjectRecord& w = want.objects[i];
    EXPECT_EQ(r.id, w.id);
    EXPECT_EQ(r.name, w.name);
    EXPECT_EQ(r.class_name, w.class_name);
    EXPECT_EQ(r.category, w.category);
    EXPECT_EQ(r.kind, w.kind);
    EXPECT_EQ(r.yolo_class, w.yolo_class);
    EXPECT_EQ(r.asset, w.asset);
    EXPECT_TRUE(r.pose.isApprox(w.pose, 1e-12)) << i;
    EXPECT_TRUE(r.extent.isApprox(w.extent)) << i;
  }
}

TEST(Objects, TextOfOneObject) {
  ObjectsFile f;
  f.scenario = "s";
  ObjectRecord r;
  r.id = 4;
  r.name = "chair_1";
  r.class_name = "chair";
  r.category = "dynamic";
  r.kind = "pushable";
  r.yolo_class = 2;
  r.extent = Eigen::AlignedBox3d(Eigen::Vector3d(-0.5, -0.5, 0), Eigen::Vector3d(0.5, 0.5, 1));
  f.objects = {r};
  EXPECT_EQ(format_objects(f),
            "{\n \"instances\": [\n  {\n   \"category\": \"dynamic\",\n   \"class\": \"chair\",\n"
            "   \"extent\": {\n    \"max\": [\n     0.5,\n     0.5,\n     1.0\n    ],\n"
            "    \"min\": [\n     -0.5,\n     -0.5,\n     0.0\n    ]\n   },\n   \"id\": 4,\n"
            "   \"kind\": \"pushable\",\n   \"name\": \"chair_1\",\n   \"pose\": {\n"
            "    \"q_xyzw\": [\n     0.0,\n     0.0,\n     0.0,\n     1.0\n    ],\n"
            "    \"t\": [\n     0.0,\n     0.0,\n     0.0\n    ]\n   },\n   \"yolo_class\": 2\n"
            "  }\n ],\n \"scenario\": \"s\"\n}\n");
}

TEST(Objects, MalformedFilesNameTheFileAndTheInstance) {
  const std::string dir = testing::new_test_folder();
  EXPECT_EQ(error_of([&] { read_objects(dir); }),
            dir +
                "/objects.json: cannot open file (the dataset's objects; not a simulated "
                "dataset?)");
  const std::string good = format_objects(two_objects());
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const struct {
    std::string text, error;
  } cases[] = {
      {with("\"class\": \"person\"", "\"klass\": \"person\""), ": instance 2: 'class' is missing"},
      {with("\"id\": 2", "\"id\": 1"), ": instance 2: id 1 is listed twice"},
      {with("\"id\": 2", "\"id\": 0"), ": instance 2: id 0 is not an instance id (1..65535)"},
      {with("\"id\": 2", "\"id\": 2.5"), ": instance 2: 'id' is not a whole number"},
      {with("\"yolo_class\": 0", "\"yolo_class\": \"person\""),
       ": instance 2: 'yolo_class' is not a whole number"},
      {with("\"instances\"", "\"objects\""), ": 'instances' is missing or not a list"},
      {"{\"scenario\": \"s\", \"instances\": [{\"id\": 1, \"name\": \"a\", \"class\": \"b\", "
       "\"category\": \"c\", \"kind\": \"d\", \"yolo_class\": 0, \"pose\": {\"t\": [0, 0], "
       "\"q_xyzw\": [0, 0, 0, 1]}}]}",
       ": instance 1: pose: 't' is not an array of 3 numbers"},
      {"{\"scenario\": \"s\", \"instances\": [{\"id\": 1, \"name\": \"a\", \"class\": \"b\", "
       "\"category\": \"c\", \"kind\": \"d\", \"yolo_class\": 0, \"pose\": {\"t\": [0, 0, 0], "
       "\"q_xyzw\": [0, 0, 0, 2]}}]}",
       ": instance 1: pose quaternion norm 2.000000 is not 1"},
  };
  for (const auto& c : cases) {
    testing::write_text(dir, "objects.json", c.text);
    EXPECT_EQ(error_of([&] { read_objects(dir); }), dir + "/objects.json" + c.error) << c.text;
  }
  testing::write_text(dir, "objects.json", "{\n \"scenario\": \"s\",\n \"instances\": [,]\n}\n");
  EXPECT_EQ(error_of([&] { read_objects(dir); }).rfind(dir + "/objects.json:3: not valid JSON", 0),
            0u);
}

}  // namespace
}  // namespace depot::dataset
