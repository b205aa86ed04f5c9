// Ctrl-C handling for long runs: a SIGINT handler that only sets a flag, which the sweep and the
// writer poll. The program then stops cleanly (temporary files removed) instead of dying mid-write.
#pragma once

#include <atomic>

#include "core/check.hpp"

namespace railtab {

// Thrown when a run stops because the interrupt flag was set.
class Interrupted : public Error {
 public:
  using Error::Error;
};

// The process-wide flag the SIGINT handler sets.
std::atomic<bool>& interrupt_flag();

// Installs the SIGINT handler for its lifetime and restores the previous one afterwards. A second
// Ctrl-C falls back to the default action (terminate) for a run that does not react.
class SigintGuard {
 public:
  SigintGuard();
  ~SigintGuard();
  SigintGuard(const SigintGuard&) = delete;
  SigintGuard& operator=(const SigintGuard&) = delete;

 private:
  void (*previous_)(int);
};

}  // namespace railtab
