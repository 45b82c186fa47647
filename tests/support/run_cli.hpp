#pragma once
// Runs the real `crowdlab` binary on an argument list and captures exit code, stdout and stderr,
// the way a user's shell script would.
#include <sys/wait.h>

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

inline CliResult run_cli(const std::vector<std::string>& args) {
  static int counter = 0;
  const auto dir = binary_dir() / "test-scratch" / "cli-io";
  std::filesystem::create_directories(dir);
  const auto out_path = dir / ("out" + std::to_string(getpid()) + "_" + std::to_string(counter) + ".txt");
  const auto err_path = dir / ("err" + std::to_string(getpid()) + "_" + std::to_string(counter++) + ".txt");
  std::string cmd = shell_quote(crowdlab_exe().string());
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

}  // namespace crowdlab::test
