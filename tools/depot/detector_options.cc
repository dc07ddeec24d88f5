#include "tools/depot/detector_options.h"

namespace depot::cli {

void add_detector_set_option(CLI::App* cmd, std::vector<YamlOverride>& overrides,
                             const std::string& help) {
  cmd->add_option_function<std::vector<std::string>>(
      "--detector-set",
      [&overrides](const std::vector<std::string>& texts) {
        for (const auto& t : texts) overrides.push_back(parse_yaml_override(t, "--detector-set"));
      },
      help);
}

}  // namespace depot::cli
