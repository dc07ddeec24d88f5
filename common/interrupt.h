#pragma once
// Ctrl-C handling for long jobs: the first SIGINT/SIGTERM sets a flag that
// loops poll (throwing depot::Error so staged outputs are cleaned up).
#include <atomic>
#include <csignal>

#include "common/error.h"

namespace depot {

inline std::atomic<bool>& interrupt_flag() {
  static std::atomic<bool> flag{false};
  return flag;
}

inline void install_interrupt_handler() {
  auto handler = [](int) { interrupt_flag().store(true); };
  std::signal(SIGINT, handler);
  std::signal(SIGTERM, handler);
}

inline void throw_if_interrupted(const std::string& what) {
  if (interrupt_flag().load()) fail(what, "interrupted");
}

}  // namespace depot
