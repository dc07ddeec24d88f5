#pragma once
// Paths written in configuration files (scenarios, detector configs).
//
// A path is relative to the folder of the file that names it, unless it
// starts with "${DEPOT_SHARED_DATA}": the folder of the shared real data
// (pretrained models, TUM timestamps and trajectories). That folder is the
// environment variable DEPOT_SHARED_DATA when set, otherwise the one the
// build was configured with (../shared/data beside the source tree), so a
// checkout anywhere can run once it is told where the data is.
#include <string>

namespace depot {

inline constexpr const char* kSharedDataVariable = "DEPOT_SHARED_DATA";

// The shared data folder: $DEPOT_SHARED_DATA, or the configured default.
std::string shared_data_dir();

// `value` from a configuration file in folder `config_dir`, made usable:
// "${DEPOT_SHARED_DATA}/x" -> shared_data_dir() + "/x"; a relative path ->
// config_dir/value; an absolute path unchanged. Lexically normalised.
std::string resolve_config_path(const std::string& value, const std::string& config_dir);

// A file shipped with the project (e.g. "scenes/depot.yaml"): defaults that
// configuration files need not name resolve here, never relative to a
// user's file, so a copied scenario still finds them. The folder is
// $DEPOT_HOME when set, otherwise the source tree the build came from.
std::string project_file(const std::string& relative);

// True when `value` names the shared data folder (for error hints).
bool names_shared_data(const std::string& value);

}  // namespace depot
