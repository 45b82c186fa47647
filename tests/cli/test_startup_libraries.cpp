// Issue 31 (session 19): `crowdlab` starts without FFmpeg's libraries. Linked, libavcodec and libavformat
// loaded about 130 shared libraries at every start (127 ms of CPU of `crowdlab version`'s 192 ms on the
// 2-core VM, ~300 ms under the sanitizers); framework/media/libav.hpp loads them when a video is first
// written or read. The dynamic loader's own trace (LD_DEBUG=files, glibc) says which libraries a run opened.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_startup_libraries {

using namespace crowdlab;
namespace fs = std::filesystem;

namespace {

/// The dynamic loader's trace of the files `crowdlab ARGS` opened (stderr, with the command's own output),
/// and its exit code.
std::pair<int, std::string> loader_trace(const std::string& args) {
  const fs::path dir = test::scratch_dir("startup_libraries");
  const fs::path trace = dir / "trace.txt";
  const std::string cmd = "LD_DEBUG=files " + test::shell_quote(test::crowdlab_exe().string()) + " " + args +
                          " >/dev/null 2>" + test::shell_quote(trace.string()) + " </dev/null";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::slurp(trace)};
}

bool opened(const std::string& trace, const std::string& library) {
  return trace.find("file=" + library) != std::string::npos;
}

}  // namespace

TEST_CASE("crowdlab starts without FFmpeg's libraries and loads them for a video", "[cli][media]") {
  const auto [validate_rc, validate] = loader_trace("validate " + test::shell_quote(test::tiny_spec()));
  CHECK(validate_rc == 0);
  // The trace works: the libraries the binary links are in it.
  REQUIRE(opened(validate, "libyaml-cpp"));
  CHECK_FALSE(opened(validate, "libavcodec"));
  CHECK_FALSE(opened(validate, "libavformat"));
  CHECK_FALSE(opened(validate, "libswscale"));

  const fs::path clip = test::scratch_dir("startup_libraries_clip") / "clip.mp4";
  const auto [render_rc, render] = loader_trace(
      "-q render --synthetic 2 --width 64 --height 48 --max-frames 3 -o " + test::shell_quote(clip.string()));
  INFO(render.substr(0, 2000));
  CHECK(render_rc == 0);
  CHECK(opened(render, "libavcodec"));
  CHECK(opened(render, "libavformat"));
  CHECK(fs::file_size(clip) > 0);
}

}  // namespace test_startup_libraries
