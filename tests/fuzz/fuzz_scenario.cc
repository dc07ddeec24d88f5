// libFuzzer target: scenario YAML files (sim/scenario/scenario_loader.h),
// read and validated without the simulator (no MuJoCo in this target).
#include <cstddef>
#include <cstdint>
#include <string>

#include "sim/scenario/scenario_loader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("scenario.yaml", data, size);
  depot::fuzz::expect_clean(path, [&] {
    depot::sim::Scenario s = depot::sim::load_scenario(path);
    depot::sim::apply_dynamic_load(s, 2.5);
  });
  return 0;
}
