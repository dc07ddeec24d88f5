#pragma once
// Reading whitespace-separated text records (the detections file, the
// dataset's boxes.txt): one record a line, blank lines and '#' comments
// skipped, a trailing '\r' ignored.
#include <istream>
#include <sstream>
#include <string>
#include <vector>

namespace depot::slam {

// Calls row(where, fields) for each record line of `in`, where is
// "<path>:<line number>" for error messages and fields are the line's
// whitespace-separated words.
template <typename Row>
void for_each_record(std::istream& in, const std::string& path, Row row) {
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
    row(where, fields);
  }
}

}  // namespace depot::slam
