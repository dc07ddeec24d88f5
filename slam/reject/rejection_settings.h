#pragma once
// Every setting of RejectionParams a user may change, each named once, here:
// its key (`--rejection-set KEY=VALUE`, a sweep's `rejection.KEY`), its type
// and range, what it does and which modes it acts in. The program's own
// flags for some of them (`--background-margin`, ...), --rejection-set, the
// sweeps' choice of which levels a mode's run depends on, and the help all
// read this table.
#include <string>
#include <vector>

#include "common/yaml_overrides.h"
#include "slam/reject/rejection_filter.h"

namespace depot::slam {

struct RejectionSetting {
  enum class Kind { kFlag, kInteger, kReal, kPersonMask };
  const char* key;
  Kind kind;
  double lo = 0, hi = 0;  // kInteger, kReal: the accepted range
  const char* unit = "";  // "m", "px", "frames", ... ("" = none)
  bool in_full = false, in_masked = false;
  const char* help = "";
  // Its field in the parameters (the one of its kind that is set).
  bool& (*flag)(RejectionParams&) = nullptr;
  int& (*integer)(RejectionParams&) = nullptr;
  float& (*real)(RejectionParams&) = nullptr;

  bool acts_in(RejectionMode mode) const {
    return (in_full && mode == RejectionMode::kFull) ||
           (in_masked && mode == RejectionMode::kMasked);
  }
};

// The table, in the order the help lists it.
const std::vector<RejectionSetting>& rejection_settings();
// The setting named `key`, or nullptr.
const RejectionSetting* find_rejection_setting(const std::string& key);

// Sets `setting.key` to its YAML value in `params`. Throws Error("<where>:
// ...") for an unknown key, a value of the wrong type or out of range.
void apply_rejection_setting(RejectionParams& params, const YamlOverride& setting,
                             const std::string& where);

// "background_margin, ego_flow, ...": every key, for help and errors.
std::string rejection_setting_keys();

}  // namespace depot::slam
