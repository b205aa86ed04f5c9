// SPDX-License-Identifier: Apache-2.0
// Runs gnuplot without a shell: posix_spawnp with an argument vector, the script on its standard
// input through a socket pair (send with MSG_NOSIGNAL: a gnuplot that dies early cannot kill us
// with SIGPIPE), paths quoted for gnuplot's own string syntax.
#include "charts/gnuplot.hpp"

#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

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

// gnuplot reads `script` from its standard input; returns its wait status.
int spawn_gnuplot(const std::string& script, const std::filesystem::path& script_path) {
  int sv[2];
  RAILTAB_CHECK(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) == 0, "gnuplot for {}: socketpair: {}",
                script_path.string(), std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, sv[1], STDIN_FILENO);  // dup2 clears close-on-exec
  char arg0[] = "gnuplot";
  char* argv[] = {arg0, nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(sv[1]);
  if (rc != 0) {
    ::close(sv[0]);
    RAILTAB_CHECK(rc != ENOENT, "gnuplot not found: run scripts/install-deps.sh (package gnuplot-nox)");
    throw Error(fmt::format("cannot start gnuplot for {}: {}", script_path.string(), std::strerror(rc)));
  }
  std::size_t sent = 0;
  while (sent < script.size()) {
    const ssize_t n = ::send(sv[0], script.data() + sent, script.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // gnuplot stopped reading: its exit status says why
    sent += static_cast<std::size_t>(n);
  }
  ::close(sv[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

}  // namespace

std::string gnuplot_quote(const std::filesystem::path& path) {
  std::string text = path.string();
  RAILTAB_CHECK(text.find_first_of(std::string("\n\r\0", 3)) == std::string::npos,
                "path \"{}\" cannot be given to gnuplot (it holds a newline or NUL character)", text);
  if (path.is_relative() && !text.empty() && (text[0] == '<' || text[0] == '|')) text = "./" + text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("''") : std::string(1, c);
  return quoted + "'";
}

std::string scene_title(const std::string& name, const std::string& description) {
  return description.empty() ? name : name + " (" + description + ")";
}

std::string gnuplot_text(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n' || c == '\r' || c == '\0') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out;
}

void run_gnuplot(const std::filesystem::path& script_path, const std::string& script,
                 const std::filesystem::path& png) {
  write_text_file(script_path, with_output(script, png));
  OutputFile image(png);
  const int status = spawn_gnuplot(with_output(script, image.temporary()), script_path);
  RAILTAB_CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0, "gnuplot failed on {} (wait status {})",
                script_path.string(), status);
  image.commit();
}

}  // namespace railtab
