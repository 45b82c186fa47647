// The MPFB2 asset subset shipped in framework/body/assets/mpfb2: it holds exactly the macro targets the
// body sampler reaches, it gives the same bodies as the full MPFB2 folder (when ../shared has one), and a
// missing or corrupt file is reported by name. Each vertex's shape anchor is the nearest body vertex.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "framework/body/mpfb2_body.hpp"
#include "framework/body/sample_mpfb2_bodies.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_mpfb2_assets {

using namespace crowdlab;
namespace fs = std::filesystem;

namespace {

const Mpfb2Model& shipped_model() {
  static const std::shared_ptr<const Mpfb2Model> model = Mpfb2Model::load(shipped_mpfb2_dir());
  return *model;
}

/// Target names (as Mpfb2Model::target takes them) of every .target.gz file under `dir`.
std::set<std::string> target_files(const fs::path& dir) {
  const fs::path root = dir / "targets" / "macrodetails";
  std::set<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string rel = fs::relative(e.path(), root).generic_string();
    const std::string suffix = ".target.gz";
    if (e.is_regular_file() && rel.size() > suffix.size() && rel.ends_with(suffix))
      names.insert(rel.substr(0, rel.size() - suffix.size()));
  }
  return names;
}

/// Every target the sampler's parameter ranges select (sample_mpfb2_bodies.hpp): a grid over each range
/// that includes its ends and the interior of every macro.json part, and every dominant ethnic group.
std::set<std::string> reachable_targets(const Mpfb2Model& model) {
  std::set<std::string> names;
  Mpfb2ShapeParams p;
  for (double gender : {0.0, 1.0})
    for (double age : {0.5, 0.6, 0.75})
      for (double muscle : {0.1, 0.3, 0.5, 0.7, 0.9})
        for (double weight : {0.1, 0.3, 0.5, 0.7, 0.9})
          for (double height : {0.0, 0.25, 0.5, 0.75, 1.0})
            for (double proportions : {0.5, 0.75, 1.0})
              for (int dominant = 0; dominant < 3; ++dominant) {
                p.gender = gender, p.age = age, p.muscle = muscle, p.weight = weight, p.height = height;
                p.proportions = proportions;
                p.african = dominant == 0 ? 0.7 : 0.15;
                p.asian = dominant == 1 ? 0.7 : 0.15;
                p.caucasian = dominant == 2 ? 0.7 : 0.15;
                for (const auto& [name, weight_of_target] : macro_target_weights(model, p))
                  names.insert(name);
              }
  return names;
}

}  // namespace

TEST_CASE("the shipped MPFB2 subset holds exactly the macro targets the body sampler reaches") {
  const std::set<std::string> shipped = target_files(shipped_mpfb2_dir());
  const std::set<std::string> reached = reachable_targets(shipped_model());
  for (const std::string& name : reached) {
    INFO("reached but not shipped: " << name);
    CHECK(shipped.count(name) == 1);
  }
  for (const std::string& name : shipped) {
    INFO("shipped but never reached: " << name);
    CHECK(reached.count(name) == 1);
  }
  CHECK(shipped.size() == 156);  // 36 universal + 12 ethnic + 72 height + 36 ideal-proportion targets
  for (const char* file : {"LICENSE.md", "LICENSE.ASSETS.md"}) CHECK(fs::exists(shipped_mpfb2_dir() / file));
}

TEST_CASE("the shipped subset builds the same bodies as the full MPFB2 assets") {
  const fs::path full = test::shared_data("mpfb2");
  if (full.empty()) return;
  const auto full_model = Mpfb2Model::load(full);
  Mpfb2ShapeParams p;
  p.gender = 0.0;
  p.age = 0.7;
  p.muscle = 0.8;
  p.weight = 0.3;
  p.height = 0.8;
  p.proportions = 0.9;
  p.african = 0.8, p.asian = 0.1, p.caucasian = 0.1;
  const Mpfb2Body a = make_mpfb2_body(shipped_model(), p);
  const Mpfb2Body b = make_mpfb2_body(*full_model, p);
  CHECK(a.height_m == b.height_m);
  CHECK(a.mesh.rest_vertices_m == b.mesh.rest_vertices_m);
  CHECK(a.mesh.rest_joints_m == b.mesh.rest_joints_m);
  for (int j = 0; j < kJointCount; ++j)
    CHECK(a.shape.capsules[static_cast<size_t>(j)].radius_m ==
          b.shape.capsules[static_cast<size_t>(j)].radius_m);
}

TEST_CASE("a missing or corrupt MPFB2 asset is an InputError naming the file") {
  const fs::path dir = test::scratch_dir("mpfb2-broken");
  const fs::path src = shipped_mpfb2_dir();
  auto message_of_load = [&] {
    try {
      Mpfb2Model::load(dir);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  fs::create_directories(dir / "3dobjs");
  CHECK_THAT(message_of_load(), Catch::Contains("base.obj"));
  fs::copy_file(src / "3dobjs" / "base.obj", dir / "3dobjs" / "base.obj");
  CHECK_THAT(message_of_load(), Catch::Contains("rig.mixamo.json"));
  fs::create_directories(dir / "rigs" / "standard");
  fs::copy_file(src / "rigs" / "standard" / "rig.mixamo.json", dir / "rigs" / "standard" / "rig.mixamo.json");
  std::ofstream(dir / "rigs" / "standard" / "weights.mixamo.json")
      << "{\"weights\": {\"mixamorig:Hips\": [[0, ";
  CHECK_THAT(message_of_load(), Catch::Contains("weights.mixamo.json"));
  fs::copy_file(src / "rigs" / "standard" / "weights.mixamo.json",
                dir / "rigs" / "standard" / "weights.mixamo.json", fs::copy_options::overwrite_existing);
  CHECK_THAT(message_of_load(), Catch::Contains("macro.json"));
  fs::create_directories(dir / "targets" / "macrodetails");
  fs::copy_file(src / "targets" / "macrodetails" / "macro.json",
                dir / "targets" / "macrodetails" / "macro.json");
  const auto model = Mpfb2Model::load(dir);
  // A target that is missing, and one cut short (a truncated gzip stream).
  const std::string name = "universal-female-young-averagemuscle-averageweight";
  try {
    model->target(name);
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains(name + ".target.gz"));
  }
  const fs::path good = src / "targets" / "macrodetails" / (name + ".target.gz");
  const std::string bytes = test::slurp(good);
  std::ofstream(dir / "targets" / "macrodetails" / (name + ".target.gz"), std::ios::binary)
      << bytes.substr(0, bytes.size() / 2);
  try {
    model->target(name);
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains(name + ".target.gz"));
  }
}

TEST_CASE("a numeric bone parent in the MPFB2 rig names the rig file and key, not the output") {
  // Was "stage 'animation' (.../baseline.glb): [json.exception.type_error.302] type must be string, but is
  // number" (issue 33).
  const fs::path dir = test::scratch_dir("mpfb2-rig-parent");
  const fs::path src = shipped_mpfb2_dir();
  fs::create_directories(dir / "3dobjs");
  fs::create_directories(dir / "rigs" / "standard");
  fs::copy_file(src / "3dobjs" / "base.obj", dir / "3dobjs" / "base.obj",
                fs::copy_options::overwrite_existing);
  const fs::path rig = dir / "rigs" / "standard" / "rig.mixamo.json";
  std::ifstream in(src / "rigs" / "standard" / "rig.mixamo.json");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string from = "\"parent\": \"mixamorig:Neck\"";
  REQUIRE(text.find(from) != std::string::npos);
  text.replace(text.find(from), from.size(), "\"parent\": 5");
  std::ofstream(rig, std::ios::trunc) << text;
  try {
    Mpfb2Model::load(dir);
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains(rig.string() + ": bones.") &&
                                          Catch::Contains(".parent: must be a string") &&
                                          Catch::Contains("got a number"));
  }
}

TEST_CASE("mpfb2 model: every vertex's shape anchor is its nearest body vertex, as a scan chooses it") {
  const Mpfb2Model& model = shipped_model();
  const auto& vertices = model.base().vertices;
  const std::vector<int>& body = model.body_vertices();
  const std::vector<int>& anchor = model.shape_anchor();
  REQUIRE(anchor.size() == vertices.size());
  std::vector<bool> is_body(vertices.size(), false);
  for (int b : body) is_body[static_cast<size_t>(b)] = true;
  int checked = 0, wrong = 0;
  for (size_t v = 0; v < vertices.size(); ++v) {
    if (is_body[v]) {
      wrong += anchor[v] != static_cast<int>(v);
      continue;
    }
    if (v % 7 != 0) continue;  // a seventh of the helper vertices: the scan is 13,000 distances each
    int best = -1;
    double best_d2 = HUGE_VAL;
    for (int b : body) {
      const double d2 = (vertices[static_cast<size_t>(b)] - vertices[v]).squaredNorm();
      if (d2 < best_d2) best_d2 = d2, best = b;
    }
    wrong += anchor[v] != best;
    ++checked;
  }
  CHECK(checked > 500);
  CHECK(wrong == 0);
}

}  // namespace test_mpfb2_assets
