// A full disk during `crowdlab run` (issue 21): every write failure names the file and the OS's reason
// ("No space left on device"), ends the run with exit code 1 (a runtime failure), removes its temporary
// file, and never leaves a truncated output that a sidecar vouches for; a retry on the still-full disk
// fails the same way and leaves nothing behind either. Before the fix: "…prov.json.tmp.<pid>: write
// failed" without the reason, "writing the MP4 trailer failed" without the file, a zero-byte temporary
// left at every retry, and crowd files that tinygltf wrote truncated without noticing.
//
// The full disk is a small tmpfs mounted for the test, filled to different points so that the failure
// lands in different writers (trajectories, crowd files, sidecars, clips, the manifest). Mounting needs
// root (CI runs as root); elsewhere the test is skipped with a warning.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "framework/core/sha256.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/tmpfs_mount.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_disk_full {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

/// A GLB is whole when its header's length (bytes 8..11, little-endian) is the file's size: tinygltf's
/// file writer ignored a failed write, so a full disk published truncated crowd files.
void check_complete_glb(const fs::path& glb) {
  std::ifstream in(glb, std::ios::binary);
  unsigned char header[12] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  const std::uintmax_t declared =
      header[8] | (header[9] << 8) | (header[10] << 16) | (static_cast<std::uintmax_t>(header[11]) << 24);
  CHECK(declared == fs::file_size(glb));
}

/// A PNG is whole when it ends with its IEND chunk.
bool complete_png(const fs::path& png) {
  const std::string bytes = slurp(png);
  return bytes.size() > 12 && bytes.compare(bytes.size() - 8, 4, "IEND") == 0;
}

/// Checks what a failed run left in `out`: no temporary, and no output whose sidecar vouches for other
/// bytes than the file holds.
void check_nothing_half_written(const fs::path& out) {
  for (const auto& e : fs::recursive_directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    INFO(e.path().string());
    CHECK(name.find(".tmp.") == std::string::npos);
    CHECK_FALSE(name.ends_with(".partial"));
    if (name.ends_with(".glb")) check_complete_glb(e.path());
    if (!name.ends_with(".prov.json")) continue;
    const fs::path output = e.path().parent_path() / name.substr(0, name.size() - 10);
    std::ifstream in(e.path());
    const nlohmann::json prov = nlohmann::json::parse(in);
    if (fs::exists(output)) CHECK(prov["output_sha256"] == sha256_file_hex(output.string()));
  }
}

}  // namespace

TEST_CASE("run on a full disk: exit 1, the file and the OS's reason named, no temporary left",
          "[pipeline][integrity]") {
  const fs::path root = scratch_dir("disk_full");
  // Full while writing: trajectories, a crowd file, a clip (its MP4 trailer), a sidecar (the tiny spec's
  // outputs take about 4 MB in all; measured with this build, the points move a little with the sizes).
  for (const std::string size : {"12k", "48k", "560k", "1120k"}) {
    INFO("tmpfs of " << size);
    const fs::path mount_point = root / size;
    const TmpfsMount disk(mount_point, size);
    if (!disk.mounted()) {
      WARN("skipped: cannot mount a tmpfs here (needs root); CI runs as root");
      return;
    }
    const fs::path out = mount_point / "out";
    for (int attempt = 1; attempt <= 2; ++attempt) {
      INFO("attempt " << attempt);
      const CliResult r = run_cli({"-q", "run", tiny_spec(), "--out", out.string()});
      INFO(r.err);
      CHECK(r.exit_code == 1);
      CHECK_THAT(r.err, Catch::Contains("No space left on device"));
      CHECK_THAT(r.err, Catch::Contains(out.string() + "/"));  // the file that could not be written
      check_nothing_half_written(out);
    }
  }
}

TEST_CASE("render on a full disk: exit 1, the file and the OS's reason named, no broken clip or frame left",
          "[pipeline][integrity]") {
  // Before the fix: "writing the MP4 trailer failed: No space left on device" without the file, a broken
  // clip left under --out, and frames that libpng could not write skipped with exit code 0 when the
  // clip still fitted.
  const fs::path root = scratch_dir("disk_full_render");
  // Full during the clip; during the first frame; during the third frame (the clip alone fits in 40k).
  for (const auto& [size, frames] :
       std::vector<std::pair<std::string, bool>>{{"4k", false}, {"4k", true}, {"40k", true}}) {
    INFO("tmpfs of " << size << (frames ? ", with --frames-png" : ""));
    const fs::path mount_point = root / (size + (frames ? "-frames" : ""));
    const TmpfsMount disk(mount_point, size);
    if (!disk.mounted()) {
      WARN("skipped: cannot mount a tmpfs here (needs root); CI runs as root");
      return;
    }
    std::vector<std::string> args{
        "-q",       "render", "--synthetic",  "4",  "--width", "160",
        "--height", "96",     "--max-frames", "15", "--out",   (mount_point / "clip.mp4").string()};
    if (frames) {
      fs::create_directories(mount_point / "frames");
      args.insert(args.end(), {"--frames-png", (mount_point / "frames").string()});
    }
    const CliResult r = run_cli(args);
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.err, Catch::Contains("No space left on device"));
    CHECK_THAT(r.err, Catch::Contains(mount_point.string() + (frames ? "/frames/frame_" : "/clip")));
    for (const auto& e : fs::recursive_directory_iterator(mount_point)) {
      INFO(e.path().string());
      const std::string name = e.path().filename().string();
      CHECK(name.find("clip") == std::string::npos);  // neither the clip nor its temporary
      if (name.ends_with(".png")) CHECK(complete_png(e.path()));
    }
  }
}

}  // namespace test_disk_full
