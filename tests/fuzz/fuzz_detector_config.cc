// libFuzzer target: the detector and segmenter YAML files: an OpenCV-dnn
// detector's (slam/detect/detector_config.h), the simulated detector's
// (slam/detect/sim_detector_config.h) and a person segmenter's
// (slam/detect/person_segmenter.h). The same bytes go to all three.
#include <cstddef>
#include <cstdint>
#include <string>

#include "slam/detect/detector_config.h"
#include "slam/detect/person_segmenter.h"
#include "slam/detect/sim_detector_config.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("detector.yaml", data, size);
  depot::fuzz::expect_clean(path, [&] { depot::slam::load_detector_config(path); });
  depot::fuzz::expect_clean(path, [&] { depot::slam::load_sim_detector_config_file(path); });
  depot::fuzz::expect_clean(path, [&] { depot::slam::load_segmenter_config(path); });
  return 0;
}
