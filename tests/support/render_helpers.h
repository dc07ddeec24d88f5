#pragma once
// Renders small real datasets in-process for the tests (OSMesa).
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace depot::test {

struct SmallRender {
  SmallRender(std::string scenario_, int frames_, int width_, bool ideal_,
              std::optional<uint64_t> seed_ = {}, bool yolo_ = false)
      : scenario(std::move(scenario_)),
        frames(frames_),
        width(width_),
        ideal(ideal_),
        seed(seed_),
        yolo(yolo_) {}
  std::string scenario;  // shipped scenario name or YAML path
  int frames;
  int width;
  bool ideal;
  std::optional<uint64_t> seed;
  bool yolo;
  // Scenario overrides, as `depot sim render --set key=value` gives them.
  std::vector<std::pair<std::string, std::string>> set;
};

// Renders and returns the dataset folder.
std::string render_small(const SmallRender& request);

std::string scenario_path(const std::string& name);
std::string depot_binary();

// The exit code and the combined stdout/stderr of one `depot` run.
struct DepotResult {
  int code;
  std::string output;
};

// Runs the built `depot` program with `args` (shell words after "depot").
DepotResult depot(const std::string& args);

}  // namespace depot::test
