#pragma once
// Runs the real `crowdlab` binary on an argument list and captures exit code, stdout and stderr,
// the way a user's shell script would.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/test_paths.hpp"

namespace crowdlab::test {

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// `timeout_s` > 0 runs it under coreutils' timeout (a hang then fails the test with exit 124 instead of
/// stalling the suite: the FIFO and /dev/zero tests of issue 32).
inline CliResult run_cli(const std::vector<std::string>& args, int timeout_s = 0) {
  static int counter = 0;
  const auto dir = binary_dir() / "test-scratch" / "cli-io";
  std::filesystem::create_directories(dir);
  const auto out_path = dir / ("out" + std::to_string(getpid()) + "_" + std::to_string(counter) + ".txt");
  const auto err_path = dir / ("err" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ".txt");
  std::string cmd = timeout_s > 0 ? "timeout -k 5 " + std::to_string(timeout_s) + " " : "";
  cmd += shell_quote(crowdlab_exe().string());
  for (const auto& a : args) cmd += " " + shell_quote(a);
  cmd += " >" + shell_quote(out_path.string()) + " 2>" + shell_quote(err_path.string()) + " </dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  return r;
}

/// Starts the real `crowdlab` binary on an argument list in the background, output to /dev/null, and
/// returns its pid (for tests that kill a run or race two of them; reap it with waitpid).
inline pid_t spawn_cli(const std::vector<std::string>& args) {
  const std::string exe = crowdlab_exe().string();
  std::vector<char*> argv{const_cast<char*>(exe.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t io;
  posix_spawn_file_actions_init(&io);
  posix_spawn_file_actions_addopen(&io, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&io, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&io, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, exe.c_str(), &io, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&io);
  return rc == 0 ? pid : -1;
}

}  // namespace crowdlab::test
