#pragma once
// One error type for the whole project: its message is the single line a user
// sees ("<file>: <problem>"), so callers add context instead of wrapping.
#include <stdexcept>
#include <string>

namespace depot {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws Error("<where>: <what>"), kept to one line: line breaks quoted
// from a user's file (a value, a key) are written as \n and \r.
[[noreturn]] inline void fail(const std::string& where, const std::string& what) {
  const std::string text = where.empty() ? what : where + ": " + what;
  std::string line;
  line.reserve(text.size());
  for (const char c : text) {
    if (c == '\n')
      line += "\\n";
    else if (c == '\r')
      line += "\\r";
    else
      line += c;
  }
  throw Error(line);
}

}  // namespace depot
