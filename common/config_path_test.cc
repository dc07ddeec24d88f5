#include "common/config_path.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace depot {
namespace {

// Sets an environment variable for one scope, restoring it after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    if (value)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (had_)
      ::setenv(name_.c_str(), old_.c_str(), 1);
    else
      ::unsetenv(name_.c_str());
  }

 private:
  std::string name_, old_;
  bool had_ = false;
};

TEST(ConfigPath, RelativeToTheConfigFolderAbsoluteUnchanged) {
  EXPECT_EQ(resolve_config_path("models/a.onnx", "/etc/depot/detectors"),
            "/etc/depot/detectors/models/a.onnx");
  EXPECT_EQ(resolve_config_path("../x/b.txt", "/etc/depot/detectors"), "/etc/depot/x/b.txt");
  EXPECT_EQ(resolve_config_path("/abs/c.txt", "/etc/depot"), "/abs/c.txt");
  EXPECT_EQ(resolve_config_path("", "/etc/depot"), "");
  EXPECT_FALSE(names_shared_data("../shared/data/x"));
}

TEST(ConfigPath, SharedDataFollowsTheEnvironmentThenTheBuildDefault) {
  {
    ScopedEnv env(kSharedDataVariable, "/data/shared");
    EXPECT_EQ(shared_data_dir(), "/data/shared");
    EXPECT_EQ(resolve_config_path("${DEPOT_SHARED_DATA}/tum/t.txt", "/anywhere"),
              "/data/shared/tum/t.txt");
    EXPECT_TRUE(names_shared_data("${DEPOT_SHARED_DATA}/tum/t.txt"));
  }
  ScopedEnv unset(kSharedDataVariable, nullptr);
  // Without the variable: the folder this build was configured with, which
  // is where the tests read the real data from.
  EXPECT_EQ(shared_data_dir(), std::string(DEPOT_SHARED_DATA));
  EXPECT_EQ(resolve_config_path("${DEPOT_SHARED_DATA}/models/m.onnx", "/anywhere"),
            std::string(DEPOT_SHARED_DATA) + "/models/m.onnx");
}

}  // namespace
}  // namespace depot
