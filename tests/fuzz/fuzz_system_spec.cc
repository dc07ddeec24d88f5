// libFuzzer target: system files, the YAML that describes another SLAM
// program under test (tools/system/system_spec.h), and expanding its
// command's placeholders.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "tests/fuzz/fuzz_support.h"
#include "tools/system/system_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("system.yaml", data, size);
  depot::fuzz::expect_clean(path, [&] {
    const depot::system::SystemSpec spec = depot::system::load_system_spec(path);
    std::map<std::string, std::string> values;
    for (const std::string& name : depot::system::system_placeholders()) values[name] = "/x";
    depot::system::expand_command(spec, values);
  });
  return 0;
}
