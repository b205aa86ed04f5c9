// SPDX-License-Identifier: Apache-2.0
// Runs gnuplot without a shell: posix_spawnp with an argument vector, the script on its standard
// input through a socket pair (send with MSG_NOSIGNAL: a gnuplot that dies early cannot kill us
// with SIGPIPE), its standard error captured through a pipe read while the script is sent; text
// from inputs written as gnuplot strings made of octal escapes.
#include "charts/gnuplot.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <iostream>

#include <fmt/format.h>

#include "core/check.hpp"
#include "table/output_file.hpp"

extern char** environ;

namespace railtab {
namespace {

// The script with `set output` after its first line (the terminal: some terminals want to be set
// before the output).
std::string with_output(const std::string& script, const std::filesystem::path& png) {
  RAILTAB_CHECK(script.rfind("set terminal", 0) == 0, "gnuplot script for {} must start with 'set terminal'",
                png.string());
  const std::size_t eol = script.find('\n');
  const std::size_t split = eol == std::string::npos ? script.size() : eol + 1;
  return script.substr(0, split) + (eol == std::string::npos ? "\n" : "") + "set output " + gnuplot_quote(png) +
         "\n" + script.substr(split);
}

std::ostream* messages_stream = &std::cerr;

// gnuplot's exit status and what it wrote on its standard error (the first 64 KiB).
struct GnuplotRun {
  int status = 0;
  std::string messages;
};

void close_both(int fds[2]) {
  ::close(fds[0]);
  ::close(fds[1]);
}

// gnuplot reads `script` from its standard input; its standard error is read meanwhile (poll), so
// neither side can fill a buffer the other never drains.
GnuplotRun spawn_gnuplot(const std::string& script, const std::filesystem::path& script_path) {
  int in[2];
  RAILTAB_CHECK(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, in) == 0, "gnuplot for {}: socketpair: {}",
                script_path.string(), std::strerror(errno));
  int err[2];
  if (::pipe2(err, O_CLOEXEC) != 0) {
    const int e = errno;
    close_both(in);
    throw Error(fmt::format("gnuplot for {}: pipe: {}", script_path.string(), std::strerror(e)));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in[1], STDIN_FILENO);  // dup2 clears close-on-exec
  posix_spawn_file_actions_adddup2(&actions, err[1], STDERR_FILENO);
  char arg0[] = "gnuplot";
  char* argv[] = {arg0, nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(in[1]);
  ::close(err[1]);
  if (rc != 0) {
    ::close(in[0]);
    ::close(err[0]);
    RAILTAB_CHECK(rc != ENOENT, "gnuplot not found: run scripts/install-deps.sh (package gnuplot-nox)");
    throw Error(fmt::format("cannot start gnuplot for {}: {}", script_path.string(), std::strerror(rc)));
  }
  constexpr std::size_t kKeep = 64 * 1024;
  GnuplotRun run;
  int to_gnuplot = in[0];
  int from_gnuplot = err[0];
  std::size_t sent = 0;
  if (script.empty()) {
    ::close(to_gnuplot);
    to_gnuplot = -1;
  }
  while (to_gnuplot >= 0 || from_gnuplot >= 0) {
    pollfd fds[2] = {{to_gnuplot, POLLOUT, 0}, {from_gnuplot, POLLIN, 0}};
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (to_gnuplot >= 0 && fds[0].revents != 0) {
      const ssize_t n = ::send(to_gnuplot, script.data() + sent, script.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n > 0) sent += static_cast<std::size_t>(n);
      // Sent in full, or gnuplot stopped reading (its exit status says why): end of its input.
      if (sent == script.size() || (n < 0 && errno != EINTR && errno != EAGAIN)) {
        ::close(to_gnuplot);
        to_gnuplot = -1;
      }
    }
    if (from_gnuplot >= 0 && fds[1].revents != 0) {
      char buffer[4096];
      const ssize_t n = ::read(from_gnuplot, buffer, sizeof buffer);
      if (n > 0 && run.messages.size() < kKeep) {
        run.messages.append(buffer, std::min(static_cast<std::size_t>(n), kKeep - run.messages.size()));
      }
      if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) {
        ::close(from_gnuplot);
        from_gnuplot = -1;
      }
    }
  }
  if (to_gnuplot >= 0) ::close(to_gnuplot);
  if (from_gnuplot >= 0) ::close(from_gnuplot);
  while (::waitpid(pid, &run.status, 0) < 0 && errno == EINTR) {
  }
  return run;
}

// The last non-empty line of gnuplot's messages (its error), for the exception.
std::string last_message(const std::string& messages) {
  const std::size_t end = messages.find_last_not_of(" \n\r\t");
  if (end == std::string::npos) return "no message";
  const std::size_t newline = messages.rfind('\n', end);
  const std::size_t start = newline == std::string::npos ? 0 : newline + 1;
  return messages.substr(start, end + 1 - start);
}

}  // namespace

void set_gnuplot_messages(std::ostream& out) { messages_stream = &out; }

void run_gnuplot(const std::filesystem::path& script_path, const std::string& script,
                 const std::filesystem::path& png) {
  const std::string problem = gnuplot_script_problem(script);
  RAILTAB_CHECK(problem.empty(), "gnuplot script {} refused: {}", script_path.string(), problem);
  write_text_file(script_path, with_output(script, png));
  OutputFile image(png);
  GnuplotRun run = spawn_gnuplot(with_output(script, image.temporary()), script_path);
  // gnuplot names the file it was given, the temporary, which is gone when the message is read:
  // its messages name the chart asked for.
  const std::string temporary = image.temporary().string();
  for (std::size_t at = run.messages.find(temporary); at != std::string::npos;
       at = run.messages.find(temporary, at + png.string().size()))
    run.messages.replace(at, temporary.size(), png.string());
  RAILTAB_CHECK(WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0, "gnuplot failed on {} (wait status {}): {}",
                script_path.string(), run.status, last_message(run.messages));
  image.commit();
  if (!run.messages.empty()) *messages_stream << "gnuplot on " << script_path.string() << ": " << run.messages;
}

}  // namespace railtab
