#pragma once
// Reading whitespace-separated text records (the detections file, the
// dataset's boxes.txt and object_poses.txt): one record a line, blank lines and '#' comments
// skipped, a trailing '\r' ignored.
#include <istream>
#include <sstream>
#include <string>
#include <vector>

namespace depot {

// Calls row(line_number, where, fields) for each record line of `in`, where
// is "<path>:<line number>" for error messages and fields are the line's
// whitespace-separated words.
template <typename Row>
void for_each_numbered_record(std::istream& in, const std::string& path, Row row) {
  std::string text;
  int line_no = 0;
  while (std::getline(in, text)) {
    ++line_no;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const auto first = text.find_first_not_of(" \t");
    if (first == std::string::npos || text[first] == '#') continue;
    const std::string where = path + ":" + std::to_string(line_no);
    std::istringstream ss(text);
    std::vector<std::string> fields;
    for (std::string s; ss >> s;) fields.push_back(s);
    row(line_no, where, fields);
  }
}

// The same without the line number: row(where, fields).
template <typename Row>
void for_each_record(std::istream& in, const std::string& path, Row row) {
  for_each_numbered_record(
      in, path, [&](int, const std::string& where, const std::vector<std::string>& fields) {
        row(where, fields);
      });
}

}  // namespace depot
