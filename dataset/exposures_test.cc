#include "dataset/exposures.h"

#include <gtest/gtest.h>

#include "common/testing/error_of.h"
#include "dataset/test_folder.h"

namespace depot::dataset {
namespace {

TEST(Exposures, RoundTripInFrameOrder) {
  const std::string dir = testing::new_test_folder();
  const std::vector<ExposureRecord> want = {
      {1.0, 0.0123456, 1.0, 1.0}, {1.0333333, 0.03, 2.5, 0.25}, {1.0666667, 0.0001, 8.0, 0.0}};
  write_exposures(dir, "dim", want);
  const std::vector<ExposureRecord> read = read_exposures(dir);
  ASSERT_EQ(read.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_NEAR(read[i].timestamp, want[i].timestamp, 5e-7) << i;
    EXPECT_NEAR(read[i].exposure, want[i].exposure, 1e-9) << i;
    EXPECT_NEAR(read[i].gain, want[i].gain, 1e-6) << i;
    EXPECT_NEAR(read[i].light, want[i].light, 1e-6) << i;
  }
}

TEST(Exposures, MalformedLinesNameTheFileAndLine) {
  const std::string dir = testing::new_test_folder();
  EXPECT_EQ(error_of([&] { read_exposures(dir); }),
            dir +
                "/exposures.txt: cannot open file (exposures are written where the camera forms "
                "its colour image)");
  const struct {
    std::string line, problem;
  } cases[] = {
      {"1.0 0.01 1", "expected 4 fields (timestamp exposure gain light), found 3"},
      {"1.0 -0.01 1 1", "exposure -0.01 is negative"},
      {"1.0 0.01 0.5 1", "gain 0.5 is below 1"},
      {"1.0 0.01 1 -1", "light -1 is negative"},
      {"1.0 0.01 1 nan", "light 'nan' is not a number"},
  };
  for (const auto& c : cases) {
    testing::write_text(dir, "exposures.txt", "# header\n" + c.line + "\n");
    EXPECT_EQ(error_of([&] { read_exposures(dir); }), dir + "/exposures.txt:2: " + c.problem)
        << c.line;
  }
}

}  // namespace
}  // namespace depot::dataset
