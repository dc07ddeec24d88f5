#pragma once
// The project's promise for bad input, as one check for the CLI tests: the
// run failed and printed exactly one line, `depot: error: ...`, naming what
// the test looks for. Header-only: only test binaries (which link GoogleTest)
// include it.
#include <algorithm>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/render_helpers.h"

namespace depot::test {

// Any non-zero exit code.
inline constexpr int kAnyFailure = -1;

inline void expect_one_error_line(const DepotResult& r, const std::vector<std::string>& needles,
                                  int code = kAnyFailure) {
  if (code == kAnyFailure) {
    EXPECT_NE(r.code, 0) << r.output;
  } else {
    EXPECT_EQ(r.code, code) << r.output;
  }
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_THAT(r.output, testing::StartsWith("depot: error: "));
  for (const std::string& needle : needles) EXPECT_THAT(r.output, testing::HasSubstr(needle));
}

inline void expect_one_error_line(const DepotResult& r, const std::string& needle,
                                  int code = kAnyFailure) {
  expect_one_error_line(r, std::vector<std::string>{needle}, code);
}

}  // namespace depot::test
