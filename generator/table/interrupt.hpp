// SPDX-License-Identifier: Apache-2.0
// Ctrl-C and SIGTERM handling for long runs (SIGTERM is what timeout, systemd and Slurm send): a
// handler that only sets a flag, which the sweep and the writer poll. The program then stops cleanly (temporary files removed) instead of dying mid-write.
#pragma once

#include <atomic>

#include "core/check.hpp"

namespace railtab {

// Thrown when a run stops because the interrupt flag was set.
class Interrupted : public Error {
 public:
  using Error::Error;
};

// The process-wide flag the SIGINT and SIGTERM handler sets.
std::atomic<bool>& interrupt_flag();

// The signal that set the flag under the current guard (SIGINT or SIGTERM), 0 if none.
int interrupt_signal();

// Installs the SIGINT and SIGTERM handler for its lifetime and restores the previous ones
// afterwards. A second signal falls back to the default action (terminate) for a run that does
// not react.
class SigintGuard {
 public:
  SigintGuard();
  ~SigintGuard();
  SigintGuard(const SigintGuard&) = delete;
  SigintGuard& operator=(const SigintGuard&) = delete;

 private:
  void (*previous_)(int);
  void (*previous_term_)(int);
};

}  // namespace railtab
