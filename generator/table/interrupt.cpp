// The SIGINT flag and its guard (interrupt.hpp).
#include "table/interrupt.hpp"

#include <csignal>

namespace railtab {

std::atomic<bool>& interrupt_flag() {
  static std::atomic<bool> flag{false};
  static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
  return flag;
}

namespace {
void on_sigint(int) {
  interrupt_flag().store(true);
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C terminates at once
}
}  // namespace

SigintGuard::SigintGuard() : previous_(std::signal(SIGINT, on_sigint)) {}

SigintGuard::~SigintGuard() { std::signal(SIGINT, previous_ == SIG_ERR ? SIG_DFL : previous_); }

}  // namespace railtab
