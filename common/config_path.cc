#include "common/config_path.h"

#include <cstdlib>
#include <filesystem>

namespace fs = std::filesystem;

namespace depot {
namespace {

const std::string kPlaceholder = std::string("${") + kSharedDataVariable + "}";

}  // namespace

std::string shared_data_dir() {
  const char* env = std::getenv(kSharedDataVariable);
  if (env && *env) return env;
  return DEPOT_SHARED_DATA_DEFAULT;
}

std::string project_file(const std::string& relative) {
  const char* env = std::getenv("DEPOT_HOME");
  const fs::path root = env && *env ? fs::path(env) : fs::path(DEPOT_PROJECT_DIR);
  return (root / relative).lexically_normal().string();
}

bool names_shared_data(const std::string& value) {
  return value.compare(0, kPlaceholder.size(), kPlaceholder) == 0;
}

std::string resolve_config_path(const std::string& value, const std::string& config_dir) {
  if (value.empty()) return value;
  fs::path p;
  if (names_shared_data(value)) {
    std::string rest = value.substr(kPlaceholder.size());
    while (!rest.empty() && rest.front() == '/') rest.erase(0, 1);
    p = fs::path(shared_data_dir()) / rest;
  } else {
    p = value;
  }
  if (p.is_relative()) p = fs::path(config_dir.empty() ? "." : config_dir) / p;
  return p.lexically_normal().string();
}

}  // namespace depot
