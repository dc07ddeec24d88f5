#include "eval/keypoint_file.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>

#include "common/error.h"

namespace depot::eval {
namespace {

const char* const kHeader =
    "frame,timestamp,x,y,octave,set,kept,depth_m,on_moving,boundary,instance\n";

// Timestamps are matched as the dataset's lists write them: to 1 us.
std::string stamp_key(double t) {
  return fmt::format("{:.6f}", t);
}

std::string trim(const std::string& s) {
  const size_t begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return s.substr(begin, s.find_last_not_of(" \t\r") - begin + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

double parse_number(const std::string& text, const std::string& column, const std::string& where) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  if (text.empty() || end == begin || *end != '\0' || errno == ERANGE)
    fail(where, column + " is not a number: '" + text + "'");
  if (!std::isfinite(v)) fail(where, column + " is not a finite number: '" + text + "'");
  return v;
}

// The header's column of each name; fails on a repeated or missing one.
struct Columns {
  std::map<std::string, size_t> index;
  size_t count = 0;
  std::optional<size_t> find(const std::string& name) const {
    auto it = index.find(name);
    return it == index.end() ? std::nullopt : std::optional<size_t>(it->second);
  }
};

Columns read_header(const std::string& line, const std::string& where) {
  Columns c;
  const std::vector<std::string> names = split_fields(line);
  c.count = names.size();
  for (size_t i = 0; i < names.size(); ++i)
    if (!c.index.emplace(names[i], i).second)
      fail(where, "column '" + names[i] + "' appears twice in the header");
  for (const char* required : {"timestamp", "x", "y", "kept"})
    if (!c.index.count(required))
      fail(where, std::string("the header has no '") + required +
                      "' column (required: timestamp,x,y,kept; optional: octave,response,set)");
  return c;
}

}  // namespace

KeypointFile read_keypoint_file(const std::string& path, const KeypointFrames& frames) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open the keypoint file");
  std::map<std::string, double> frame_of;  // key -> the dataset's timestamp
  for (double t : frames.timestamps) frame_of[stamp_key(t)] = t;

  KeypointFile file;
  file.path = path;
  std::string line;
  if (!std::getline(in, line) || trim(line).empty())
    fail(path, "empty: expected a header line naming the columns (timestamp,x,y,kept ...)");
  const Columns columns = read_header(line, path + ":1");
  const size_t c_timestamp = *columns.find("timestamp"), c_x = *columns.find("x"),
               c_y = *columns.find("y"), c_kept = *columns.find("kept");
  const std::optional<size_t> c_octave = columns.find("octave"),
                              c_response = columns.find("response"), c_set = columns.find("set");
  file.has_octave = c_octave.has_value();
  file.has_response = c_response.has_value();
  file.has_set = c_set.has_value();

  size_t line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (trim(line).empty()) continue;
    const std::string where = path + ":" + std::to_string(line_no);
    const std::vector<std::string> f = split_fields(line);
    if (f.size() != columns.count)
      fail(where, "expected " + std::to_string(columns.count) + " fields as the header has, got " +
                      std::to_string(f.size()));
    KeypointRow row;
    row.line = line_no;
    const double t = parse_number(f[c_timestamp], "timestamp", where);
    auto frame = frame_of.find(stamp_key(t));
    if (frame == frame_of.end())
      fail(where, "timestamp " + f[c_timestamp] + " is not a frame of " + frames.dataset);
    row.timestamp = frame->second;
    const double x = parse_number(f[c_x], "x", where), y = parse_number(f[c_y], "y", where);
    if (x < 0 || y < 0 || x >= frames.image.width || y >= frames.image.height)
      fail(where, "point (" + f[c_x] + ", " + f[c_y] + ") is outside the " +
                      std::to_string(frames.image.width) + "x" +
                      std::to_string(frames.image.height) + " image");
    row.x = static_cast<float>(x);
    row.y = static_cast<float>(y);
    if (f[c_kept] != "0" && f[c_kept] != "1")
      fail(where, "kept must be 0 (rejected) or 1 (kept), got '" + f[c_kept] + "'");
    row.kept = f[c_kept] == "1";
    if (c_octave) {
      const double octave = parse_number(f[*c_octave], "octave", where);
      if (octave < 0 || octave > 64 || octave != std::floor(octave))
        fail(where, "octave must be a pyramid level 0, 1, 2 ..., got '" + f[*c_octave] + "'");
      row.octave = static_cast<int>(octave);
    }
    if (c_response) row.response = parse_number(f[*c_response], "response", where);
    if (c_set) row.set = f[*c_set];
    file.rows.push_back(std::move(row));
  }
  if (in.bad()) fail(path, "read error");
  if (file.rows.empty()) fail(path, "has a header but no keypoint rows");
  return file;
}

void write_keypoint_header(std::ostream& out) {
  out << kHeader;
}

void write_keypoint_row(std::ostream& out, const WrittenKeypoint& r) {
  out << fmt::format("{},{:.6f},{:.9g},{:.9g},{},{},{},{:.4f},", r.frame, r.timestamp,
                     static_cast<double>(r.keypoint.pt.x), static_cast<double>(r.keypoint.pt.y),
                     r.keypoint.octave, r.set, r.kept ? 1 : 0, static_cast<double>(r.depth_m));
  if (r.truth)
    out << (r.truth->on_moving ? 1 : 0) << ',' << (r.truth->boundary ? 1 : 0) << ','
        << r.truth->instance;
  else
    out << ",,";
  out << '\n';
}

}  // namespace depot::eval
