#include "slam/io/frame_states_file.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"

namespace depot::slam {

std::string frame_states_path(const std::string& trajectory_path) {
  const std::filesystem::path p(trajectory_path);
  if (p.extension() == ".txt") return (p.parent_path() / p.stem()).string() + ".states.txt";
  return trajectory_path + ".states.txt";
}

std::string format_frame_states(const std::vector<StampedFrameState>& states,
                                const std::string& header) {
  std::string text;
  if (!header.empty()) text += "# " + header + "\n";
  text +=
      "# timestamp state (tracked = NEW_MAP, OK, RELOCALIZED: in the trajectory; untracked = "
      "NOT_INITIALIZED, LOST, ABANDONED, OTHER_MAP; see slam/track/tracking_state.h)\n";
  char line[64];
  for (const StampedFrameState& s : states) {
    std::snprintf(line, sizeof(line), "%.6f %s\n", s.timestamp, frame_state_name(s.state));
    text += line;
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
    std::string stamp, name, extra;
    fields >> stamp >> name;
    if (name.empty() || (fields >> extra)) fail(where, "expected 2 fields (timestamp state)");
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
    out.push_back({t, *state});
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

}  // namespace depot::slam
