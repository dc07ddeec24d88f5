// libFuzzer target: a sweep's description as its folder stores it
// (sweep.json, read back by `sweep resume` and `sweep status` as
// tools/harness/plan/sweep_plan.cc's read_spec does) and the --vary / --set
// levels of `depot sweep run` (tools/harness/plan/sweep_spec.h): each line of
// the input is one such option's value.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/fuzz/fuzz_support.h"
#include "tools/harness/plan/sweep_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string path = depot::fuzz::write_input("sweep.json", data, size);
  depot::fuzz::expect_clean(path, [&] {
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
      depot::fail(path, std::string("corrupt sweep description: ") + e.what());
    }
    depot::harness::sweep_spec_from_json(j, path);
  });
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    depot::fuzz::expect_clean("--vary",
                              [&] { depot::harness::parse_sweep_parameter(line, "--vary"); });
  return 0;
}
