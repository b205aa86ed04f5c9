// SPDX-License-Identifier: Apache-2.0
// Corruption campaign (run by scripts/corruption_campaign.sh): N copies of a
// table, each with one byte replaced by a different random value, each loaded through the C API
// in a child process under a memory limit, then queried at fixed states and compared with the
// pristine table. Counts per outcome:
//   refused    railtab_lookup_open returned an error (the wanted outcome for a corrupt byte)
//   same       loaded, every answer bit-identical to the pristine table's (a byte nobody reads)
//   different  loaded, some answer differs: a SILENT WRONG ANSWER (must be 0)
//   crash      the child died of a signal (must be 0); hang: killed after --timeout seconds
//   big_alloc  some single allocation request (malloc & co., including libhdf5's) exceeded
//              2 x the file size (must be 0); counted whatever the outcome. Floor: the largest
//              request of the pristine load (libhdf5 allocates its ~515 KB metadata cache
//              structure on every H5Fopen, whatever the file; larger than 2 x a small table)
// Optionally (--inspect RAILTAB) the same file is given to `railtab inspect` in a child with the
// same memory limit: crashes, hangs and peak-memory growth over 2 x the file size are counted.
// Usage: railtab_lookup_corruption TABLE.h5 [--flips N] [--seed S] [--memory-mib M]
//                                  [--timeout S] [--inspect PATH] [--keep DIR]
// Exit status 0 when crash, hang, different and big_alloc are all 0.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "railtab_lookup.h"

// ---- Allocation watch: every allocation of the process (libhdf5's too) goes through here. ----
extern "C" {
void* __libc_malloc(size_t);
void* __libc_calloc(size_t, size_t);
void* __libc_realloc(void*, size_t);
void* __libc_memalign(size_t, size_t);
void __libc_free(void*);
}

namespace {
std::atomic<std::size_t> g_largest_request{0};  // largest single request seen [B]
void note(std::size_t bytes) {
  std::size_t seen = g_largest_request.load(std::memory_order_relaxed);
  while (bytes > seen && !g_largest_request.compare_exchange_weak(seen, bytes)) {
  }
}
}  // namespace

extern "C" {
void* malloc(size_t n) {
  note(n);
  return __libc_malloc(n);
}
void* calloc(size_t n, size_t size) {
  note(size != 0 && n > SIZE_MAX / size ? SIZE_MAX : n * size);
  return __libc_calloc(n, size);
}
void* realloc(void* p, size_t n) {
  note(n);
  return __libc_realloc(p, n);
}
void free(void* p) { __libc_free(p); }
void* memalign(size_t align, size_t n) {
  note(n);
  return __libc_memalign(align, n);
}
void* aligned_alloc(size_t align, size_t n) {
  note(n);
  return __libc_memalign(align, n);
}
int posix_memalign(void** out, size_t align, size_t n) {
  note(n);
  void* p = __libc_memalign(align, n);
  if (!p) return ENOMEM;
  *out = p;
  return 0;
}
}

namespace {

enum Outcome : int { kRefused = 0, kSame = 1, kDifferent = 2, kSetupError = 3 };

struct Report {
  int outcome = kSetupError;
  std::size_t largest_request = 0;  // [B]
};

// Fixed query states spread over the table (default state, then each tabulated axis at 5
// positions inside its range, others at their default), both wheels, all slots.
std::vector<unsigned char> answers(railtab_lookup_table* t) {
  std::vector<unsigned char> out;
  railtab_lookup_state base;
  railtab_lookup_default_state(t, &base);
  std::vector<railtab_lookup_state> states{base};
#ifndef RAILTAB_LOOKUP_ERROR_RANGE
  // Built against a lookup without introspection (an older lookup): y across the fixture.
  for (int k = 0; k < 21; ++k) {
    states.push_back(base);
    states.back().y = -0.0095 + 0.00095 * k;
    states.back().xi = 0.001 * (k % 5);
  }
  struct { int n_axes = 0, n_fixed = 0, n_slots = 0, checksums_verified = 0; } info;
#else
  railtab_lookup_table_info info;
  railtab_lookup_info(t, &info);
  for (int a = 0; a < info.n_axes; ++a) {
    const char* name = nullptr;
    std::size_t n = 0;
    const double* nodes = nullptr;
    railtab_lookup_axis(t, a, &name, nullptr, &n, &nodes);
    for (int k = 0; k < 5; ++k) {
      railtab_lookup_state s = base;
      const double x = nodes[0] + (nodes[n - 1] - nodes[0]) * (0.05 + 0.2 * k + 0.013 * a);
      const std::string v = name;
      (v == "y" ? s.y : v == "roll" ? s.roll : v == "load" ? s.load : v == "xi" ? s.xi
                                                : v == "eta" ? s.eta : s.phi) = x;
      states.push_back(s);
    }
  }
#endif
  for (const auto& s : states) {
    for (int w = 0; w < 2; ++w) {
      railtab_lookup_result r;
      std::memset(&r, 0, sizeof r);
      railtab_lookup_query(t, w, &s, &r);
      const auto* p = reinterpret_cast<const unsigned char*>(&r);
      out.insert(out.end(), p, p + sizeof r);
    }
  }
  // What the table says about itself is an answer too.
  const auto* p = reinterpret_cast<const unsigned char*>(&info.n_axes);
  out.insert(out.end(), p, p + 3 * sizeof(int));
  return out;
}

std::vector<unsigned char> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>((std::istreambuf_iterator<char>(in)), {});
}

bool write_file(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

void limit_child(std::size_t memory_bytes, int timeout_s) {
  rlimit mem{memory_bytes, memory_bytes};
  setrlimit(RLIMIT_AS, &mem);
  rlimit core{0, 0};
  setrlimit(RLIMIT_CORE, &core);
  alarm(static_cast<unsigned>(timeout_s));
}

struct ChildEnd {
  bool crashed = false, hung = false;
  Report report;
  long max_rss_kib = 0;
};

// Loads `path` in a child process; the child compares with `reference` and reports via a pipe.
ChildEnd load_in_child(const std::string& path, const std::vector<unsigned char>& reference,
                       std::size_t memory_bytes, int timeout_s) {
  int fds[2];
  if (pipe(fds) != 0) std::exit(3);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    limit_child(memory_bytes, timeout_s);
    g_largest_request = 0;
    Report r;
    railtab_lookup_table* t = nullptr;
    if (railtab_lookup_open(path.c_str(), RAILTAB_LOOKUP_LINEAR, &t) != RAILTAB_LOOKUP_OK) {
      r.outcome = kRefused;
    } else {
      r.outcome = answers(t) == reference ? kSame : kDifferent;
      railtab_lookup_close(t);
    }
    r.largest_request = g_largest_request.load();
    if (write(fds[1], &r, sizeof r) != static_cast<ssize_t>(sizeof r)) _exit(4);
    _exit(0);
  }
  close(fds[1]);
  ChildEnd end;
  const bool got = read(fds[0], &end.report, sizeof end.report) == static_cast<ssize_t>(sizeof end.report);
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  end.max_rss_kib = usage.ru_maxrss;
  if (WIFSIGNALED(status)) {
    end.hung = WTERMSIG(status) == SIGALRM;
    end.crashed = !end.hung;
  } else if (!got) {
    end.crashed = true;  // exited without a report
  }
  return end;
}

// `railtab inspect path` in a child (stdout/stderr to /dev/null): signal, exit code, peak RSS.
ChildEnd inspect_in_child(const std::string& railtab, const std::string& path,
                          std::size_t memory_bytes, int timeout_s) {
  const pid_t pid = fork();
  if (pid == 0) {
    limit_child(memory_bytes, timeout_s);
    std::FILE* null = std::fopen("/dev/null", "w");
    if (null) {
      dup2(fileno(null), 1);
      dup2(fileno(null), 2);
    }
    execl(railtab.c_str(), railtab.c_str(), "inspect", path.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  ChildEnd end;
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  end.max_rss_kib = usage.ru_maxrss;
  if (WIFSIGNALED(status)) {
    end.hung = WTERMSIG(status) == SIGALRM;
    end.crashed = !end.hung;
  }
  end.report.outcome = WIFEXITED(status) && WEXITSTATUS(status) == 0 ? kSame : kRefused;
  return end;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s TABLE.h5 [--flips N] [--seed S] [--memory-mib M] "
                         "[--timeout S] [--inspect RAILTAB] [--keep DIR]\n", argv[0]);
    return 2;
  }
  const std::string table = argv[1];
  int flips = 1000, timeout_s = 30;
  unsigned seed = 19;
  std::size_t memory_mib = 2048;
  std::string inspect, keep;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string opt = argv[i];
    if (opt == "--flips") flips = std::atoi(argv[i + 1]);
    else if (opt == "--seed") seed = static_cast<unsigned>(std::atoi(argv[i + 1]));
    else if (opt == "--memory-mib") memory_mib = static_cast<std::size_t>(std::atoll(argv[i + 1]));
    else if (opt == "--timeout") timeout_s = std::atoi(argv[i + 1]);
    else if (opt == "--inspect") inspect = argv[i + 1];
    else if (opt == "--keep") keep = argv[i + 1];
    else {
      std::fprintf(stderr, "unknown option %s\n", opt.c_str());
      return 2;
    }
  }
  const std::vector<unsigned char> pristine = read_file(table);
  if (pristine.empty()) {
    std::fprintf(stderr, "cannot read %s\n", table.c_str());
    return 2;
  }
  const std::size_t memory = memory_mib << 20;

  railtab_lookup_table* t = nullptr;
  if (railtab_lookup_open(table.c_str(), RAILTAB_LOOKUP_LINEAR, &t) != RAILTAB_LOOKUP_OK) {
    std::fprintf(stderr, "the pristine table does not load: %s\n", railtab_lookup_last_error());
    return 2;
  }
#ifdef RAILTAB_LOOKUP_ERROR_RANGE
  railtab_lookup_table_info info;
  railtab_lookup_info(t, &info);
#else
  struct { int checksums_verified = 0; } info;
#endif
  const std::vector<unsigned char> reference = answers(t);
  railtab_lookup_close(t);
  // The pristine load's own largest allocation and the inspect baseline, for the report.
  const ChildEnd base = load_in_child(table, reference, memory, timeout_s);
  const std::size_t big = std::max(2 * pristine.size(), base.report.largest_request);
  long inspect_base_kib = 0;
  if (!inspect.empty()) inspect_base_kib = inspect_in_child(inspect, table, memory, timeout_s).max_rss_kib;

  const std::string work = "/tmp/railtab_corruption_" + std::to_string(getpid()) + ".h5";
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> where(0, pristine.size() - 1);
  std::uniform_int_distribution<int> delta(1, 255);
  int count[4] = {}, crash = 0, hang = 0, big_alloc = 0;
  int i_crash = 0, i_hang = 0, i_big = 0;
  std::vector<std::string> notes;
  for (int k = 0; k < flips; ++k) {
    std::vector<unsigned char> bytes = pristine;
    const std::size_t at = where(rng);
    const int d = delta(rng);
    bytes[at] = static_cast<unsigned char>(bytes[at] ^ d);
    if (!write_file(work, bytes)) return 2;
    const ChildEnd e = load_in_child(work, reference, memory, timeout_s);
    std::string what;
    if (e.crashed) ++crash, what = "CRASH";
    else if (e.hung) ++hang, what = "HANG";
    else ++count[e.report.outcome];
    if (!e.crashed && !e.hung && e.report.outcome == kDifferent) what = "DIFFERENT";
    if (e.report.largest_request > big) ++big_alloc, what += " BIG_ALLOC";
    if (!inspect.empty()) {
      const ChildEnd ie = inspect_in_child(inspect, work, memory, timeout_s);
      if (ie.crashed) ++i_crash, what += " INSPECT_CRASH";
      if (ie.hung) ++i_hang, what += " INSPECT_HANG";
      if ((ie.max_rss_kib - inspect_base_kib) * 1024L > static_cast<long>(big))
        ++i_big, what += " INSPECT_BIG_MEMORY";
    }
    if (!what.empty()) {
      char line[160];
      std::snprintf(line, sizeof line, "  flip %d: byte %zu ^= 0x%02x: %s", k, at, d, what.c_str());
      notes.emplace_back(line);
      if (!keep.empty()) write_file(keep + "/flip_" + std::to_string(k) + ".h5", bytes);
    }
  }
  std::remove(work.c_str());
  std::printf("corruption campaign: %s (%zu bytes, checksums %s), %d single-byte changes, seed %u, "
              "memory limit %zu MiB\n", table.c_str(), pristine.size(),
              info.checksums_verified ? "verified" : "ABSENT (legacy table)", flips, seed, memory_mib);
  std::printf("C API: refused %d, loaded same answers %d, loaded DIFFERENT answers %d, crash %d, "
              "hang %d, allocation over max(2 x file size, pristine load's largest %zu B) %d\n",
              count[kRefused], count[kSame], count[kDifferent], crash, hang,
              base.report.largest_request, big_alloc);
  if (!inspect.empty())
    std::printf("railtab inspect: crash %d, hang %d, peak memory over baseline + 2 x file size %d\n",
                i_crash, i_hang, i_big);
  for (const auto& n : notes) std::printf("%s\n", n.c_str());
  const bool ok = crash == 0 && hang == 0 && count[kDifferent] == 0 && big_alloc == 0 &&
                  count[kSetupError] == 0 && i_crash == 0 && i_hang == 0 && i_big == 0;
  std::printf("%s\n", ok ? "campaign: PASS" : "campaign: FAIL");
  return ok ? 0 : 1;
}
