#include "tests/support/render_helpers.h"

#include <filesystem>

#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"
#include "tests/support/dataset_reader.h"

namespace depot::test {

std::string scenario_path(const std::string& name) {
  if (std::filesystem::exists(name)) return name;
  return std::string(DEPOT_SOURCE_DIR) + "/scenarios/" + name + ".yaml";
}

std::string depot_binary() {
  return std::string(DEPOT_BINARY_DIR) + "/tools/depot/depot";
}

DepotResult depot(const std::string& args) {
  DepotResult r;
  r.code = run_command(depot_binary() + " " + args, &r.output);
  return r;
}

std::string render_small(const SmallRender& r) {
  std::vector<YamlOverride> overrides;
  for (const auto& [key, value] : r.set) overrides.push_back({key, value});
  sim::Scenario scenario = sim::load_scenario(scenario_path(r.scenario), overrides);
  sim::RenderRequest request;
  request.dataset.output = temp_path(scenario.name);
  request.dataset.yolo_export = r.yolo;
  request.frames = r.frames;
  request.width = r.width;
  request.ideal = r.ideal;
  request.seed = r.seed;
  request.progress = false;
  sim::render_dataset(scenario, request);
  return request.dataset.output;
}

}  // namespace depot::test
