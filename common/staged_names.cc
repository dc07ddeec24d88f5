#include "common/staged_names.h"

#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

namespace depot {
namespace {

std::mutex& names_mutex() {
  static std::mutex m;
  return m;
}

std::vector<std::pair<std::string, std::string>>& names() {
  static std::vector<std::pair<std::string, std::string>> pairs;
  return pairs;
}

// A sweep stages many runs; the table keeps the recent ones only.
constexpr size_t kKept = 4096;

}  // namespace

void remember_staged_name(const std::string& staging_path, const std::string& final_path) {
  std::lock_guard<std::mutex> lock(names_mutex());
  auto& pairs = names();
  if (pairs.size() >= kKept) pairs.erase(pairs.begin(), pairs.begin() + kKept / 2);
  pairs.emplace_back(staging_path, final_path);
}

std::string with_final_names(std::string message) {
  std::vector<std::pair<std::string, std::string>> pairs;
  {
    std::lock_guard<std::mutex> lock(names_mutex());
    pairs = names();
  }
  // Longest first: a staged file inside a staged folder keeps its own name.
  std::sort(pairs.begin(), pairs.end(),
            [](const auto& a, const auto& b) { return a.first.size() > b.first.size(); });
  for (const auto& [staging, final_path] : pairs) {
    if (staging.empty()) continue;
    for (size_t at = message.find(staging); at != std::string::npos;
         at = message.find(staging, at + final_path.size()))
      message.replace(at, staging.size(), final_path);
  }
  return message;
}

}  // namespace depot
