#include "sim/scenario/shipped_scenarios.h"

#include <cstdlib>
#include <filesystem>

#include "common/config_path.h"
#include "common/error.h"

namespace fs = std::filesystem;

namespace depot::sim {

std::string scenarios_folder() {
  if (const char* env = std::getenv("DEPOT_SCENARIOS")) return env;
  return project_file("scenarios");
}

std::string resolve_scenario(const std::string& arg) {
  std::error_code ec;
  if (fs::is_regular_file(arg, ec)) return arg;
  fs::path shipped = fs::path(scenarios_folder()) / (arg + ".yaml");
  if (fs::path(arg).extension() != ".yaml" && fs::is_regular_file(shipped, ec))
    return shipped.string();
  fail(arg, "scenario not found (neither a file nor a shipped scenario; see `depot sim list`)");
}

}  // namespace depot::sim
