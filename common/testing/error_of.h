#pragma once
// Test helper (header-only): the message of the depot::Error a call throws.
#include <string>

#include "common/error.h"

namespace depot {

// The message of the depot::Error that `f` throws, or `none` when it throws
// none.
template <typename F>
std::string error_of(F f, const std::string& none = "") {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return none;
}

}  // namespace depot
