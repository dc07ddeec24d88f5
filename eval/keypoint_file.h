#pragma once
// The per-keypoint file: one CSV row per keypoint a SLAM system extracted,
// saying where it is and whether the system kept it, so that any system's
// rejection can be scored against a simulated dataset's labels
// (eval/keypoint_score.h, `depot eval rejection`). This unit owns the format:
// the built-in modes write it (`depot slam run --keypoints`) and everything
// reads it here.
//
// A header line names the columns, in any order. Required: timestamp (the
// frame's rgb timestamp), x, y (image pixels, pixel centres at integers) and
// kept (1 = kept, 0 = rejected as dynamic). Optional: octave (the pyramid
// level the keypoint was found at, 0 when absent), response, set. Other
// columns are ignored, e.g. those the built-in modes add (frame, depth_m,
// on_moving, boundary, instance).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace depot::eval {

struct KeypointRow {
  double timestamp = 0.0;
  float x = 0.0f, y = 0.0f;
  bool kept = true;
  int octave = 0;
  double response = 0.0;  // 0 when the file has no response column
  std::string set;        // "" when the file has no set column
  size_t line = 0;        // where in the file (1 = the header)
};

struct KeypointFile {
  std::string path;
  std::vector<KeypointRow> rows;
  bool has_octave = false, has_response = false, has_set = false;
};

// What the rows must fit: the dataset's frames and image size. Points are
// in the image when 0 <= x < width and 0 <= y < height.
struct KeypointFrames {
  std::string dataset;             // named in errors
  std::vector<double> timestamps;  // the frames' rgb timestamps (matched to 1 us)
  cv::Size image;
};

// Reads and checks the file. Throws depot::Error naming the file, the line
// and the problem: no header, a missing or repeated column, a row with the
// wrong number of fields, a non-numeric or non-finite value, kept other than
// 0/1, a negative octave, a timestamp that is no frame of the dataset, a
// point outside the image, or no rows at all.
KeypointFile read_keypoint_file(const std::string& path, const KeypointFrames& frames);

// Writing, as the built-in modes do: the header, then one row per keypoint.
// x and y are written with 9 significant digits, which give back the same
// float, so re-scoring the file sees the same pixels as the run did.
void write_keypoint_header(std::ostream& out);

struct WrittenKeypoint {
  size_t frame = 0;
  double timestamp = 0.0;
  cv::KeyPoint keypoint;
  char set = 'P';  // Z, Q or P (slam/reject)
  bool kept = true;
  float depth_m = 0.0f;
  // On simulated data, the keypoint's truth (eval/motion_truth.h); else the
  // columns are left empty.
  struct Truth {
    bool on_moving = false, boundary = false;
    uint16_t instance = 0;
  };
  std::optional<Truth> truth;
};
void write_keypoint_row(std::ostream& out, const WrittenKeypoint& row);

}  // namespace depot::eval
