#include "slam/io/frame_states_file.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace depot::slam {

namespace {

// A file beside a trajectory: "run.txt" -> "run<suffix>", any other name
// with the suffix appended.
std::string beside_trajectory(const std::string& trajectory_path, const std::string& suffix) {
  const std::filesystem::path p(trajectory_path);
  if (p.extension() == ".txt") return (p.parent_path() / p.stem()).string() + suffix;
  return trajectory_path + suffix;
}

}  // namespace

std::string frame_states_path(const std::string& trajectory_path) {
  return beside_trajectory(trajectory_path, ".states.txt");
}

std::string atlas_trajectory_path(const std::string& trajectory_path) {
  return beside_trajectory(trajectory_path, ".atlas.txt");
}

std::string format_frame_states(const std::vector<StampedFrameState>& states,
                                const std::string& header) {
  std::string text;
  if (!header.empty()) text += "# " + header + "\n";
  text +=
      "# timestamp state [map] (tracked = NEW_MAP, OK, RELOCALIZED: in the trajectory; untracked "
      "= NOT_INITIALIZED, LOST, ABANDONED, OTHER_MAP; see slam/track/tracking_state.h; map: the "
      "atlas map of a frame with a pose, 0 = the trajectory's)\n";
  for (const StampedFrameState& s : states) {
    if (s.map >= 0)
      text += fmt::format("{:.6f} {} {}\n", s.timestamp, frame_state_name(s.state), s.map);
    else
      text += fmt::format("{:.6f} {}\n", s.timestamp, frame_state_name(s.state));
  }
  return text;
}

std::vector<StampedFrameState> read_frame_states(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a folder, not a states file");
  std::ifstream in(path);
  if (!in) fail(path, "cannot open file");
  std::vector<StampedFrameState> out;
  std::string text;
  int line_no = 0;
  double previous = -INFINITY;
  while (std::getline(in, text)) {
    ++line_no;
    const std::string where = path + ":" + std::to_string(line_no);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream fields(text);
    std::string stamp, name, map, extra;
    fields >> stamp >> name >> map;
    if (name.empty() || (fields >> extra))
      fail(where, "expected 2 or 3 fields (timestamp state [map])");
    char* end = nullptr;
    const double t = std::strtod(stamp.c_str(), &end);
    if (end == stamp.c_str() || *end != '\0' || !std::isfinite(t))
      fail(where, "'" + stamp + "' is not a timestamp");
    if (t <= previous) fail(where, "timestamps must increase");
    previous = t;
    const std::optional<FrameState> state = parse_frame_state(name);
    if (!state)
      fail(where, "unknown state '" + name +
                      "' (expected NOT_INITIALIZED, NEW_MAP, OK, RELOCALIZED, LOST, ABANDONED or "
                      "OTHER_MAP)");
    StampedFrameState f{t, *state, -1};
    if (!map.empty()) {
      if (!has_pose(f.state))
        fail(where, "a " + name + " frame has no pose, so no map ('" + map + "')");
      char* map_end = nullptr;
      const long m = std::strtol(map.c_str(), &map_end, 10);
      const bool number = map_end != map.c_str() && *map_end == '\0' && m >= 0 && m < 1000000;
      if (!number) fail(where, "'" + map + "' is not a map number (0, 1, ...)");
      if (is_tracked(f.state) && m != 0)
        fail(where, "a tracked frame is in map 0 (the trajectory's), not " + map);
      if (f.state == FrameState::kOtherMap && m == 0)
        fail(where, "an OTHER_MAP frame is not in map 0 (the trajectory's)");
      f.map = static_cast<int>(m);
    }
    out.push_back(f);
  }
  if (in.bad()) fail(path, "read error");
  if (out.empty()) fail(path, "no frames in states file");
  return out;
}

TrackedShare tracked_share(const std::vector<StampedFrameState>& states) {
  TrackedShare s;
  s.frames = states.size();
  for (const StampedFrameState& f : states) s.tracked += is_tracked(f.state);
  return s;
}

std::vector<int> maps_of_posed_frames(const std::vector<StampedFrameState>& states) {
  std::vector<int> maps;
  bool named = false;
  for (const StampedFrameState& f : states) {
    if (!has_pose(f.state)) continue;
    maps.push_back(f.map);
    named = named || f.map >= 0;
  }
  if (!named) maps.clear();
  return maps;
}

}  // namespace depot::slam
