#pragma once
// Runs one fuzz case in a child process under a wall-clock limit and a memory cap, and says how it
// ended: exit code, signal, timed out, or over the memory cap. The child either runs the `crowdlab`
// binary (exec) or calls a function in-process (for loaders no subcommand reaches alone, such as BVH).
//
// Memory cap: the child's resident set is sampled every 2 ms and the child killed past kRssCap_mb.
// Release builds also get RLIMIT_AS (kAddressSpaceCap_mb), which turns one huge allocation into
// std::bad_alloc (exit 1, a failure). AddressSanitizer reserves terabytes of address space, so under
// the sanitizers RLIMIT_AS is not set and ASan's own max_allocation_size_mb / hard_rss_limit_mb stop a
// huge allocation with a report (again not exit 0 or 2, a failure).
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "tests/support/test_paths.hpp"

namespace crowdlab::test {

inline constexpr long kRssCap_mb = 1024;
inline constexpr long kAddressSpaceCap_mb = 4096;

struct LimitedRun {
  int exit_code = -1;  ///< when the child exited
  int signal = 0;      ///< when a signal ended it (not our kill)
  bool timed_out = false;
  bool over_memory = false;
  long peak_rss_mb = 0;
  double seconds = 0.0;
  std::string err;  ///< its stderr

  /// Under AddressSanitizer a deadly signal never reaches the parent: the sanitizer's handler prints
  /// "AddressSanitizer: SEGV on ..." (or BUS, FPE, ILL) and exits 1. Returns that signal's number, or 0.
  int signal_caught_by_sanitizer() const {
    static constexpr std::pair<const char*, int> kNames[] = {{"AddressSanitizer: SEGV", SIGSEGV},
                                                             {"AddressSanitizer: BUS", SIGBUS},
                                                             {"AddressSanitizer: FPE", SIGFPE},
                                                             {"AddressSanitizer: ILL", SIGILL}};
    for (const auto& [name, number] : kNames)
      if (err.find(name) != std::string::npos) return number;
    return 0;
  }

  /// The fuzz contract (issue 21): exit 0, or exit 2 with a message, never a signal, a hang, memory
  /// beyond the cap, another exit code, or a sanitizer report.
  std::string violation() const {
    if (timed_out) return "did not finish within the time limit (hang?)";
    if (over_memory) return "went over the memory cap of " + std::to_string(kRssCap_mb) + " MB resident";
    if (signal != 0) return "was killed by signal " + std::to_string(signal);
    if (const int caught = signal_caught_by_sanitizer(); caught != 0)
      return "was killed by signal " + std::to_string(caught) + " (caught and reported by AddressSanitizer)";
    if (err.find("AddressSanitizer") != std::string::npos || err.find("runtime error:") != std::string::npos)
      return "made a sanitizer report";
    if (exit_code != 0 && exit_code != 2) return "exited with code " + std::to_string(exit_code);
    if (exit_code == 2 && err.find("error") == std::string::npos) return "exited 2 without an error message";
    return "";
  }
};

inline long resident_mb(pid_t pid) {
  char path[64];
  std::snprintf(path, sizeof path, "/proc/%d/statm", static_cast<int>(pid));
  FILE* f = std::fopen(path, "r");
  if (!f) return 0;
  long size = 0, resident = 0;
  const int got = std::fscanf(f, "%ld %ld", &size, &resident);
  std::fclose(f);
  return got == 2 ? resident * (sysconf(_SC_PAGESIZE) / 1024) / 1024 : 0;
}

/// Forks; the child redirects stdout to /dev/null and stderr to `err_file`, applies the caps and runs
/// `body` (which returns the exit code, or execs). The parent waits up to `limit_s`.
inline LimitedRun run_limited(const std::function<int()>& body, double limit_s,
                              const std::filesystem::path& err_file) {
  LimitedRun r;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const int null_fd = open("/dev/null", O_RDWR);
    const int err_fd = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(null_fd, 0);
    dup2(null_fd, 1);
    dup2(err_fd, 2);
    const rlimit no_core{0, 0};
    setrlimit(RLIMIT_CORE, &no_core);
    if (!kSanitized) {
      const rlim_t cap = static_cast<rlim_t>(kAddressSpaceCap_mb) << 20;
      const rlimit as{cap, cap};
      setrlimit(RLIMIT_AS, &as);
    }
    std::fflush(nullptr);
    _exit(body());
  }
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    r.peak_rss_mb = std::max(r.peak_rss_mb, resident_mb(pid));
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (r.peak_rss_mb > kRssCap_mb || elapsed > limit_s) {
      (r.peak_rss_mb > kRssCap_mb ? r.over_memory : r.timed_out) = true;
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!r.timed_out && !r.over_memory) {
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  }
  r.err = slurp(err_file);
  return r;
}

/// Runs `crowdlab args...` under the caps. Under the sanitizers ASan is told to refuse single
/// allocations over 2 GB and to stop past 2 GB resident, with a report.
inline LimitedRun run_crowdlab_limited(const std::vector<std::string>& args, double limit_s,
                                       const std::filesystem::path& err_file) {
  return run_limited(
      [&] {
        if (kSanitized) {
          const char* old = std::getenv("ASAN_OPTIONS");
          const std::string options = std::string(old ? old : "") + (old && *old ? ":" : "") +
                                      "max_allocation_size_mb=2048:hard_rss_limit_mb=2048";
          setenv("ASAN_OPTIONS", options.c_str(), 1);
        }
        std::vector<std::string> argv_strings{crowdlab_exe().string()};
        argv_strings.insert(argv_strings.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (std::string& s : argv_strings) argv.push_back(s.data());
        argv.push_back(nullptr);
        execv(argv[0], argv.data());
        return 127;
      },
      limit_s, err_file);
}

}  // namespace crowdlab::test
