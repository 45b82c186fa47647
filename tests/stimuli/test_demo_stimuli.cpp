// CI check of the demo's stimuli: `crowdlab run experiments/demo.yaml` regenerated at 640x360 (clips cut
// to a few frames), then, on every condition's crowd: frames are not blank, characters appear where the
// camera model predicts, and the red (overlap) pixel fraction falls from baseline to corrected.
#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <sstream>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "stimuli/render_clip.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_demo_stimuli {

using namespace crowdlab;
using namespace crowdlab::stimuli;
namespace fs = std::filesystem;

namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

/// Pixels (x, y) where two same-sized images differ by more than 6 in some channel.
bool differs_at(const BgrImage& a, const BgrImage& b, int x, int y) {
  const size_t at = 3 * (static_cast<size_t>(y) * static_cast<size_t>(a.width) + static_cast<size_t>(x));
  for (size_t k = 0; k < 3; ++k)
    if (std::abs(a.bgr[at + k] - b.bgr[at + k]) > 6) return true;
  return false;
}

}  // namespace

TEST_CASE("demo stimuli at 640x360: not blank, characters where predicted, less red once corrected",
          "[stimuli][pipeline]") {
  if (test::kSanitized) {
    // The check is about the stimuli, not memory safety: the Release run performs it, and the renderer,
    // the pipeline's render stage and overlap mode run under the sanitizers in the other stimuli and
    // pipeline tests. Regenerating the demo under ASan costs about two minutes of CI on two cores.
    WARN("skipped under sanitizers (run in the Release configuration)");
    return;
  }
  const fs::path out = test::scratch_dir("demo_stimuli");
  std::ifstream in(test::source_dir() / "experiments/demo.yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string spec = replaced(ss.str(), "resolution: [480, 270]", "resolution: [640, 360]");
  spec = replaced(spec, "duration_s: 2.0", "duration_s: 0.2");  // 3 frames per clip keep CI fast
  // The checks read the clips and the crowd files only: the metrics stage (its mesh-level measures on
  // these MPFB2 crowds) and the contact sheets were a fifth of this test's time, checked elsewhere
  // (tests/pipeline, tests/determinism), and are left out here (issue 31).
  spec = replaced(spec, "contact_sheet: true", "contact_sheet: false\n  metrics: false");
  const fs::path spec_path = out / "demo_640.yaml";
  std::ofstream(spec_path) << spec;
  const test::CliResult r = test::run_cli({"-q", "run", spec_path.string(), "--out", (out / "run").string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const StimulusManifest manifest = read_manifest((out / "run" / "manifest.csv").string());
  // 2 densities x 2 viewpoints x 2 methods, and the practice trial the demo opens with (issue 21).
  REQUIRE(manifest.entries.size() == 9u);
  CHECK(manifest.entries.front().practice);
  CHECK(manifest.entries.front().id == "practice_density-3.33_viewpoint-V1_method-baseline_rep-1");

  MannequinOptions coarse_meshes;  // 3.5 cm grid: 3x faster to build, plenty at 640 x 360
  coarse_meshes.voxel_m = 0.035;
  Renderer renderer(coarse_meshes);
  RenderOptions options;
  options.width = 640;
  options.height = 360;
  std::map<std::string, std::map<std::string, double>> red;  // density/viewpoint -> method -> mean red
  for (const StimulusEntry& e : manifest.entries) {
    INFO("stimulus " << e.id);
    CHECK(e.width == 640);
    CHECK(e.height == 360);
    CHECK(fs::file_size(out / "run" / e.file) > 1000);
    const CrowdAnimation crowd = read_crowd_glb((out / "run" / "conditions" / e.id / "crowd.glb").string());
    REQUIRE(e.frames == crowd.frame_count());
    const std::string viewpoint = e.factors.at("viewpoint");
    const int frame = crowd.frame_count() / 2;
    const Camera cam = Viewpoint(*find_viewpoint(viewpoint), crowd, options.width, options.height).at(frame);
    options.scene.overlap = false;
    options.scene.characters = true;
    const BgrImage with = render_frame(renderer, crowd, options, cam, frame);
    options.scene.characters = false;
    const BgrImage without = render_frame(renderer, crowd, options, cam, frame);
    // Not blank: the frame is not one colour, and the characters cover a visible part of it.
    int changed = 0, lo = 255, hi = 0;
    for (size_t p = 0; p < with.bgr.size(); ++p) {
      lo = std::min<int>(lo, with.bgr[p]);
      hi = std::max<int>(hi, with.bgr[p]);
    }
    for (int y = 0; y < with.height; ++y)
      for (int x = 0; x < with.width; ++x) changed += differs_at(with, without, x, y);
    CHECK(hi - lo > 60);
    CHECK(changed > 0.03 * with.width * with.height);
    // Each character's head, projected by the camera model, is drawn over the empty scene (a head
    // hidden by a nearer body still differs from the empty scene; one behind the stage, drawn in both
    // images, does not, hence 90 %).
    int heads = 0, seen = 0;
    for (const CharacterAnimation& c : crowd.characters) {
      const BoneTransforms bones = forward_kinematics(c.shape, c.frames[static_cast<size_t>(frame)]);
      const auto px = cam.project(bones[kHead].translation + Vec3(0, 0.06, 0));
      if (!px || px->x() < 0 || px->y() < 0 || px->x() >= with.width || px->y() >= with.height) continue;
      ++heads;
      seen += differs_at(with, without, static_cast<int>(px->x()), static_cast<int>(px->y()));
    }
    CHECK(heads >= static_cast<int>(crowd.characters.size()) / 2);
    CHECK(seen >= 0.9 * heads);
    // The practice crowd (its own seed) is checked like every clip above, but has no method to compare:
    // its red fraction would be measured for nothing.
    if (e.practice) continue;
    // Overlap mode: mean red-pixel fraction over every other frame of the clip (overlap mode on rendered
    // surfaces runs the mesh inside test per frame: a few seconds for 40 MPFB2 characters on 2 cores).
    options.scene.characters = true;
    options.scene.overlap = true;
    double sum = 0.0;
    int sampled = 0;
    for (int f = 0; f < crowd.frame_count(); f += 2, ++sampled) {
      double fraction = 0.0;
      render_frame(renderer, crowd, options, Viewpoint(*find_viewpoint(viewpoint), crowd, 640, 360).at(f), f,
                   &fraction);
      sum += fraction;
    }
    red[e.factors.at("density") + "/" + viewpoint][e.factors.at("method")] = sum / sampled;
  }
  for (const auto& [scene, by_method] : red) {
    INFO(scene << ": baseline " << by_method.at("baseline") << ", ours " << by_method.at("ours"));
    CHECK(by_method.at("baseline") > 0.0);
    CHECK(by_method.at("ours") < by_method.at("baseline"));
  }
}

}  // namespace test_demo_stimuli
