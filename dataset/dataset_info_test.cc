#include "dataset/dataset_info.h"

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/format_version.h"
#include "dataset/objects.h"
#include "dataset/test_folder.h"

namespace depot::dataset {
namespace {

DatasetInfo rendered_info() {
  DatasetInfo i;
  i.generator = "depot-slam simulator";
  i.scenario = "depot_walking_xyz";
  i.description = "people walking";
  i.seed = 7;
  i.world_seed = 18446744073709551615ull;  // the whole uint64 range survives
  i.frames = 300;
  i.dynamic_load = 0.5;
  i.actors_style = "mesh";
  i.props_style = "primitive";
  i.sensor = "kinect";
  i.motion = "xyz";
  i.camera_cover = {{0.09, 0.19}};
  i.covered_frames = {{3, 5}};
  return i;
}

TEST(DatasetInfo, RoundTripsEveryMember) {
  const std::string dir = testing::new_test_folder();
  write_info(dir, rendered_info());
  const std::optional<DatasetInfo> read = read_info(dir);
  ASSERT_TRUE(read);
  const DatasetInfo want = rendered_info();
  EXPECT_EQ(read->format_version, kFormatVersion);
  EXPECT_EQ(read->generator, want.generator);
  EXPECT_EQ(read->scenario, want.scenario);
  EXPECT_EQ(read->description, want.description);
  EXPECT_EQ(read->seed, want.seed);
  EXPECT_EQ(read->world_seed, want.world_seed);
  EXPECT_EQ(read->frames, want.frames);
  EXPECT_EQ(read->dynamic_load, want.dynamic_load);
  EXPECT_EQ(read->actors_style, want.actors_style);
  EXPECT_EQ(read->props_style, want.props_style);
  EXPECT_EQ(read->sensor, want.sensor);
  EXPECT_EQ(read->motion, want.motion);
  EXPECT_EQ(read->camera_cover, want.camera_cover);
  EXPECT_EQ(read->covered_frames, want.covered_frames);
}

TEST(DatasetInfo, TextOfATruthExportKeepsItsKeysInNameOrderWithTheVersion) {
  // The bytes the simulator wrote before the version existed, plus the
  // version: datasets stay byte-identical for the same scenario and seed.
  DatasetInfo i;
  i.generator = "depot-slam simulator (ground truth only)";
  i.scenario = "s";
  i.seed = 1;
  i.world_seed = 1;
  i.frames = 2;
  i.dynamic_load = 1.0;
  i.actors_style = "mesh";
  i.props_style = "mesh";
  i.motion = "static";
  EXPECT_EQ(format_info(i),
            "{\n \"actors_style\": \"mesh\",\n \"dynamic_load\": 1.0,\n \"format_version\": 1,\n"
            " \"frames\": 2,\n \"generator\": \"depot-slam simulator (ground truth only)\",\n"
            " \"motion\": \"static\",\n \"props_style\": \"mesh\",\n \"scenario\": \"s\",\n"
            " \"seed\": 1,\n \"world_seed\": 1\n}\n");
}

TEST(DatasetInfo, AFolderWithoutInfoHasNone) {
  EXPECT_FALSE(read_info(testing::new_test_folder()));
}

TEST(DatasetInfo, AnInfoWithoutVersionIsVersionOne) {
  const std::string dir = testing::new_test_folder();
  testing::write_text(dir, "info.json", "{\"scenario\": \"old\", \"seed\": 3}\n");
  const std::optional<DatasetInfo> read = read_info(dir);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->format_version, 1);
  EXPECT_EQ(read->scenario, "old");
  EXPECT_EQ(read->seed, 3u);
  EXPECT_FALSE(read->frames);
}

TEST(DatasetInfo, ANewerVersionIsRefusedByEveryReader) {
  const std::string dir = testing::new_test_folder();
  testing::write_text(dir, "info.json", "{\"format_version\": 2}\n");
  const std::string want = dir +
                           "/info.json: format_version 2 is newer than this program reads (up "
                           "to 1): update depot-slam";
  EXPECT_EQ(error_of([&] { read_info(dir); }), want);
  EXPECT_EQ(error_of([&] { read_objects(dir); }), want);
}

TEST(DatasetInfo, MalformedFilesAreOneLineNamingTheFile) {
  const std::string dir = testing::new_test_folder();
  const struct {
    std::string text, error;
  } cases[] = {
      {"{\"format_version\": 0}", "/info.json: format_version 0 is not a whole number >= 1"},
      {"{\"format_version\": 1.5}", "/info.json: format_version 1.5 is not a whole number >= 1"},
      {"[1, 2]", "/info.json: not a dataset's info file (not a JSON object)"},
      {"{\"seed\": -1}", "/info.json: 'seed' is not a seed (>= 0)"},
      {"{\"frames\": \"many\"}", "/info.json: 'frames' is not a whole number"},
      {"{\"camera_cover\": [[1]]}",
       "/info.json: 'camera_cover' is not a list of [first, last] pairs"},
      // Found by fuzzing (tests/fuzz/fuzz_dataset_info): nlohmann's
      // out_of_range escaped as another exception.
      {"{\"dynamic_load\": 1e99999}",
       "/info.json: not valid JSON: number overflow parsing '1e99999'"},
  };
  for (const auto& c : cases) {
    testing::write_text(dir, "info.json", c.text);
    EXPECT_EQ(error_of([&] { read_info(dir); }), dir + c.error) << c.text;
  }
  testing::write_text(dir, "info.json", "{\n \"seed\": 1,\n \"frames\": ]\n}\n");
  const std::string error = error_of([&] { read_info(dir); });
  EXPECT_EQ(error.rfind(dir + "/info.json:3: not valid JSON: ", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

}  // namespace
}  // namespace depot::dataset
