// SPDX-License-Identifier: Apache-2.0
// The interrupt flag and its guard (interrupt.hpp): SIGINT and SIGTERM both set it.
#include "table/interrupt.hpp"

#include <csignal>

namespace railtab {

std::atomic<bool>& interrupt_flag() {
  static std::atomic<bool> flag{false};
  static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
  return flag;
}

namespace {
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs a lock-free number");

void on_signal(int sig) {
  g_signal.store(sig);
  interrupt_flag().store(true);
  std::signal(sig, SIG_DFL);  // a second signal of the same kind terminates at once
}
}  // namespace

int interrupt_signal() { return g_signal.load(); }

SigintGuard::SigintGuard()
    : previous_(std::signal(SIGINT, on_signal)), previous_term_(std::signal(SIGTERM, on_signal)) {
  g_signal.store(0);
}

SigintGuard::~SigintGuard() {
  std::signal(SIGINT, previous_ == SIG_ERR ? SIG_DFL : previous_);
  std::signal(SIGTERM, previous_term_ == SIG_ERR ? SIG_DFL : previous_term_);
}

}  // namespace railtab
