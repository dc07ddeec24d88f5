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

// Throws Error("<where>: <what>").
[[noreturn]] inline void fail(const std::string& where, const std::string& what) {
  throw Error(where.empty() ? what : where + ": " + what);
}

}  // namespace depot
