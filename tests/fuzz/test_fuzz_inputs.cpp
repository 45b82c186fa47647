// Seeded mutation fuzzing of every loader (issue 21, "done means"): a few hundred mutations of a valid
// spec (through `validate`), BVH clip (the BVH importer and the retargeting, in a child process: no
// subcommand reads a clip alone), crowd GLB (through `correct`, `metrics`, `export-csv`, and the glTF
// motion importer) and analysis CSV (through `analyze anova`). Every run must end in exit 0, or exit 2
// with a message: never a signal, a hang, memory beyond the cap (limited_run.hpp), another exit code
// or a sanitizer report.
//
// Reproducing a failure: the message gives the seed, the case number, the mutations, the command and
// the input file, which is kept under build/test-scratch/fuzz_<kind>/<test tag>/. Run that command on that
// file, or rerun the test with CROWDLAB_FUZZ_SEED=<seed>. CROWDLAB_FUZZ_CASES=<n> changes the number of cases
// per input kind (for a longer run by hand).
//
// The hostile families of issue 32 (deep JSON in web results, GLB accessors viewing one buffer many
// times, gzip bombs, duplicate factor levels, special files as inputs, outputs that are links) are
// generated, not mutated: each case is a small input of a seeded size, and each must be refused (exit 2
// with a message, and a linked output's target untouched), within the same time and memory caps.
#include <sys/stat.h>
#include <zlib.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>

#include <nlohmann/json.hpp>
#include "framework/animation/bvh.hpp"
#include "framework/animation/gltf_motion.hpp"
#include "framework/animation/retarget.hpp"
#include "framework/body/mpfb2_model.hpp"
#include "framework/core/error.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "study_ui/web_import.hpp"
#include "tests/fuzz/limited_run.hpp"
#include "tests/fuzz/mutator.hpp"
#include "tests/support/glb_bytes.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_fuzz_inputs {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kDefaultSeed = 2021;

std::uint64_t fuzz_seed() {
  const char* s = std::getenv("CROWDLAB_FUZZ_SEED");
  return s && *s ? std::strtoull(s, nullptr, 10) : kDefaultSeed;
}

int fuzz_cases(int default_cases) {
  const char* s = std::getenv("CROWDLAB_FUZZ_CASES");
  return s && *s ? std::atoi(s) : default_cases;
}

/// Per-run wall-clock limit: the slowest valid run is under 1 s in Release on a loaded two-core machine.
double run_limit_s() {
  return kSanitized ? 90.0 : 20.0;
}

void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// One input kind's campaign: the cases, what became of them, and the violations with how to reproduce.
struct Campaign {
  std::string kind;
  std::string extension;
  fs::path dir;
  std::uint64_t seed;
  int accepted = 0, refused = 0;
  double slowest_s = 0.0;
  long peak_rss_mb = 0;
  std::vector<std::string> violations;

  Campaign(std::string kind_name, std::string ext)
      : kind(std::move(kind_name)),
        extension(std::move(ext)),
        dir(scratch_dir("fuzz_" + kind)),
        seed(fuzz_seed()) {}

  /// Case -1 is the unmutated input.
  fs::path input_path(int index) const {
    return dir / ((index < 0 ? std::string("unmutated") : "case-" + std::to_string(index)) + extension);
  }

  void record(int index, const std::string& mutations, const std::string& what, const LimitedRun& r) {
    slowest_s = std::max(slowest_s, r.seconds);
    peak_rss_mb = std::max(peak_rss_mb, r.peak_rss_mb);
    if (const std::string v = r.violation(); !v.empty()) {
      violations.push_back("fuzz seed " + std::to_string(seed) + ", " + kind + " case " +
                           std::to_string(index) + " (" + mutations + "): " + what + " " + v +
                           "; input kept at " + input_path(index).string() +
                           "\n  stderr: " + r.err.substr(0, 600));
      return;
    }
    ++(r.exit_code == 0 ? accepted : refused);
  }

  /// Runs the unmutated input, written at input_path(-1) (it must be accepted: the runs below then reach past
  /// the loaders' first checks), then `cases` mutations of it. `check(i, input_path, mutations)` runs one
  /// input and records each of its runs.
  void run(int cases, const std::function<std::string(Mutator&, std::string&)>& mutate,
           const std::function<void(int, const std::string&)>& check) {
    check(-1, "unmutated");
    INFO("the unmutated " << kind
                          << " input must be accepted: " << (violations.empty() ? "" : violations[0]));
    REQUIRE((violations.empty() && refused == 0));
    Mutator m(seed);
    for (int i = 0; i < cases; ++i) {
      std::string mutations;
      write_file(input_path(i), mutate(m, mutations));
      check(i, mutations);
    }
  }

  void report() const {
    std::printf(
        "fuzz %s: seed %llu, %d runs accepted, %d refused with exit 2, %zu violations; slowest run "
        "%.2f s, peak resident %ld MB\n",
        kind.c_str(), static_cast<unsigned long long>(seed), accepted, refused, violations.size(), slowest_s,
        peak_rss_mb);
    std::string all;
    for (const std::string& v : violations) all += v + "\n";
    INFO(all);
    CHECK(violations.empty());
  }
};

/// The exit code a CLI would give for what `body` throws, with the message on stderr.
int exit_code_of(const std::function<void()>& body) {
  try {
    body();
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "crowdlab: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "crowdlab: error: %s\n", e.what());
    return 1;
  }
}

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

}  // namespace

TEST_CASE("mutated specs through validate end in exit 0 or 2 with a message", "[fuzz]") {
  Campaign c("spec", ".yaml");
  const std::string valid = slurp(tiny_spec());
  REQUIRE(!valid.empty());
  write_file(c.input_path(-1), valid);
  const std::string deep = "\nextras: " + std::string(20000, '[') + std::string(20000, ']') + "\n";
  c.run(
      fuzz_cases(kSanitized ? 50 : 100),
      [&](Mutator& m, std::string& mutations) { return m.mutate(valid, deep, mutations); },
      [&](int i, const std::string& mutations) {
        const std::string in = c.input_path(i).string();
        c.record(i, mutations, "`crowdlab validate " + in + "`",
                 run_crowdlab_limited({"validate", in}, run_limit_s(), c.dir / "err.txt"));
      });
  c.report();
}

TEST_CASE("mutated BVH clips through the importer and retargeting end in success or InputError", "[fuzz]") {
  Campaign c("bvh", ".bvh");
  const std::string valid = slurp(source_dir() / "tests/data/fuzz/walk.bvh");
  REQUIRE(!valid.empty());
  write_file(c.input_path(-1), valid);
  const std::string deep =
      repeat("JOINT j\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n", 30000) +
      std::string(30000, '}');
  const BodyShape body = make_procedural_body({Sex::kFemale, 1.65, 1.0});
  c.run(
      fuzz_cases(200), [&](Mutator& m, std::string& mutations) { return m.mutate(valid, deep, mutations); },
      [&](int i, const std::string& mutations) {
        const fs::path path = c.input_path(i);
        const auto import = [&] { return exit_code_of([&] { (void)retarget_bvh(import_bvh(path), body); }); };
        c.record(i, mutations, "import_bvh + retarget_bvh",
                 run_limited(import, run_limit_s(), c.dir / "err.txt"));
      });
  c.report();
}

TEST_CASE("mutated crowd GLBs through correct, metrics, export-csv and the motion importer", "[fuzz]") {
  Campaign c("glb", ".glb");
  SwayingCrowdOptions o;
  o.characters = 2;
  o.frames = 4;
  CrowdAnimation crowd = make_swaying_crowd_fixture(o);
  Box stage;
  stage.center_m = Vec3(0, -0.5, 0);
  stage.half_extents_m = Vec3(2, 0.5, 2);
  crowd.environment.boxes.push_back(stage);
  write_crowd_glb(crowd, c.input_path(-1).string());
  const std::string valid = slurp(c.input_path(-1));
  REQUIRE(valid.size() > 20);
  const std::string json = glb_json(valid);
  const std::string deep = std::string(30000, '[') + std::string(30000, ']') + ",";
  c.run(
      fuzz_cases(kSanitized ? 25 : 50),
      [&](Mutator& m, std::string& mutations) {
        // Half the cases mutate the container's bytes, half the JSON inside a well-formed container.
        if (m.below(2) == 0) return m.mutate(valid, deep, mutations);
        std::string inner;
        const std::string bytes = glb_with_json(valid, m.mutate(json, deep, inner));
        mutations = "json:" + inner;
        return bytes;
      },
      [&](int i, const std::string& mutations) {
        const fs::path path = c.input_path(i);
        const std::string in = path.string(), out_glb = (c.dir / "out.glb").string(),
                          out_csv = (c.dir / "out.csv").string();
        for (const std::vector<std::string>& args :
             {std::vector<std::string>{"correct", in, "--out", out_glb},
              std::vector<std::string>{"metrics", in},
              std::vector<std::string>{"export-csv", in, "--out", out_csv}}) {
          std::string command = "`crowdlab";
          for (const std::string& a : args) command += " " + a;
          c.record(i, mutations, command + "`", run_crowdlab_limited(args, run_limit_s(), c.dir / "err.txt"));
        }
        const auto import = [&] { return exit_code_of([&] { (void)import_gltf_animation(path); }); };
        c.record(i, mutations, "import_gltf_animation",
                 run_limited(import, run_limit_s(), c.dir / "err.txt"));
      });
  c.report();
}

TEST_CASE("mutated analysis CSVs through analyze anova end in exit 0 or 2 with a message", "[fuzz]") {
  Campaign c("csv", ".csv");
  const std::string valid = slurp(source_dir() / "tests/data/analysis/ez_2x3x2.csv");
  REQUIRE(!valid.empty());
  write_file(c.input_path(-1), valid);
  const std::string deep = "\n" + std::string(100000, ',') + "\n\"" + std::string(1000, 'x');
  c.run(
      fuzz_cases(kSanitized ? 40 : 80),
      [&](Mutator& m, std::string& mutations) { return m.mutate(valid, deep, mutations); },
      [&](int i, const std::string& mutations) {
        const std::string in = c.input_path(i).string();
        c.record(i, mutations,
                 "`crowdlab analyze anova --csv " + in + " --dv DV --subject id --within A,B,D`",
                 run_crowdlab_limited(
                     {"analyze", "anova", "--csv", in, "--dv", "DV", "--subject", "id", "--within", "A,B,D"},
                     run_limit_s(), c.dir / "err.txt"));
      });
  c.report();
}

namespace {

/// A hostile family's case must be refused: exit 0 is a violation too.
void record_refusal(Campaign& c, int index, const std::string& what, const std::string& command,
                    const LimitedRun& r) {
  c.record(index, what, command, r);
  if (r.exit_code == 0)
    c.violations.push_back(c.kind + " case " + std::to_string(index) + " (" + what + "): " + command +
                           " accepted a hostile input; input kept at " + c.input_path(index).string());
}

std::string repeated_list(const std::string& item, std::size_t n) {
  std::string out = "[";
  for (std::size_t i = 0; i < n; ++i) out += (i ? ", " : "") + item;
  return out + "]";
}

}  // namespace

TEST_CASE("hostile families of issue 32 are refused with exit 2, within the caps", "[fuzz]") {
  Campaign c("hostile", ".in");
  Mutator m(c.seed);
  const int cases = fuzz_cases(kSanitized ? 3 : 6);
  const ExperimentSpec spec = load_experiment_spec(tiny_spec());
  const std::string spec_text = slurp(tiny_spec());
  const fs::path err = c.dir / "err.txt";
  int index = 0;
  // Deep JSON in web results (a stack overflow at 300,000 levels): as one document and as JSON lines.
  for (int k = 0; k < cases; ++k, ++index) {
    const std::size_t depth = std::size_t{40} << m.below(14);  // 40 .. 327,680 levels
    const std::string deep = std::string(depth, '[') + std::string(depth, ']');
    const bool lines = m.below(2) == 1;
    write_file(c.input_path(index),
               lines ? "{\"format\": \"crowdlab-web-data\", \"video\": " + deep + "}\n"
                     : "{\"format\": \"crowdlab-web-data\", \"records\": [{\"spec_hash\": " + deep + "}]}");
    const std::string file = c.input_path(index).string();
    const auto import = [&] {
      return exit_code_of([&] {
        (void)study::import_web(spec, StimulusManifest{}, {file}, {(c.dir / "out").string(), ""});
      });
    };
    record_refusal(c, index, "web results " + std::to_string(depth) + " deep", "import_web",
                   run_limited(import, run_limit_s(), err));
  }
  // GLB accessors viewing one buffer many times over (7.2 GB from a 40 MB file).
  SwayingCrowdOptions o;
  o.characters = 2;
  o.frames = 3;
  const fs::path good_glb = c.dir / "good.glb";
  write_crowd_glb(make_swaying_crowd_fixture(o), good_glb.string());
  const std::string glb = slurp(good_glb);
  for (int k = 0; k < cases; ++k, ++index) {
    nlohmann::json json = nlohmann::json::parse(glb_json(glb));
    const nlohmann::json accessor = json["accessors"][m.below(json["accessors"].size())];
    const std::size_t copies = 20000 + m.below(40000);
    for (std::size_t i = 0; i < copies; ++i) json["accessors"].push_back(accessor);
    write_file(c.input_path(index), glb_with_json(glb, json.dump()));
    record_refusal(c, index, std::to_string(copies) + " copies of an accessor", "`crowdlab metrics`",
                   run_crowdlab_limited({"metrics", c.input_path(index).string()}, run_limit_s(), err));
  }
  // Gzip bombs: shape targets that inflate far past their mesh's bound.
  for (int k = 0; k < cases; ++k, ++index) {
    const int vertices = 10 + static_cast<int>(m.below(1000));
    const std::size_t lines = 10000 + m.below(40000);
    {
      gzFile f = gzopen(c.input_path(index).c_str(), "wb9");
      const std::string line =
          m.below(2) ? "0 0.1 0.2 0.3" + std::string(100, ' ') + "\n" : "#" + std::string(120, 'z') + "\n";
      for (std::size_t i = 0; i < lines; ++i) gzputs(f, line.c_str());
      gzclose(f);
    }
    const fs::path path = c.input_path(index);
    const auto read = [&] { return exit_code_of([&] { (void)read_target_gz(path, vertices); }); };
    record_refusal(c, index, std::to_string(lines) + " lines for " + std::to_string(vertices) + " vertices",
                   "read_target_gz", run_limited(read, run_limit_s(), err));
  }
  // Duplicate factor levels, in the factors and in protocol.practice (12.5 million messages before).
  for (int k = 0; k < cases; ++k, ++index) {
    const std::size_t n = 2 + m.below(4000);
    std::string text = spec_text;
    const bool practice = m.below(2) == 1;
    if (practice)
      text.replace(text.find("outputs:"), 0, "  practice: {viewpoint: " + repeated_list("V4", n) + "}\n");
    else
      text.replace(text.find("viewpoint: [V4]"), 15, "viewpoint: " + repeated_list("V4", n));
    write_file(c.input_path(index), text);
    record_refusal(c, index, std::to_string(n) + " x V4" + (practice ? " in practice" : ""),
                   "`crowdlab validate`",
                   run_crowdlab_limited({"validate", c.input_path(index).string()}, run_limit_s(), err));
  }
  // Special files as inputs: a FIFO nobody writes (blocked for ever before), endless devices.
  const fs::path fifo = c.dir / "fifo.yaml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const std::string& input : {fifo.string(), std::string("/dev/zero"), std::string("/dev/urandom")}) {
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"validate", input},
          std::vector<std::string>{"analyze", "anova", "--csv", input, "--dv", "DV", "--subject", "id",
                                   "--within", "A"},
          std::vector<std::string>{"metrics", input}}) {
      record_refusal(c, index, input, "`crowdlab " + args[0] + " " + input + "`",
                     run_crowdlab_limited(args, run_limit_s(), err));
    }
    ++index;
  }
  // Outputs that are links (to a file outside the output folder) or FIFOs: refused, the target untouched.
  for (const std::string& kind : {std::string("link"), std::string("dangling"), std::string("fifo")}) {
    const fs::path target = c.dir / ("target-" + kind + ".csv"), out = c.dir / ("out-" + kind + ".csv");
    if (kind != "dangling") std::ofstream(target) << "keep";
    if (kind == "fifo")
      REQUIRE(::mkfifo(out.c_str(), 0600) == 0);
    else
      fs::create_symlink(target, out);
    record_refusal(
        c, index, "output " + kind, "`crowdlab export-csv --out " + out.string() + "`",
        run_crowdlab_limited({"export-csv", good_glb.string(), "--out", out.string()}, run_limit_s(), err));
    if (kind == "dangling" ? fs::exists(target) : slurp(target) != "keep")
      c.violations.push_back("export-csv wrote through the " + kind + " " + out.string());
    ++index;
  }
  c.report();
}

namespace {

/// An issue-33 family's case must be refused (record_refusal) with a message that names `place` (the input
/// file or the option) and stays short: no library's bare message, no value echoed whole.
void record_named_refusal(Campaign& c, int index, const std::string& what, const std::string& command,
                          const LimitedRun& r, const std::string& place) {
  record_refusal(c, index, what, command, r);
  if (r.exit_code == 2 && r.err.find(place) == std::string::npos)
    c.violations.push_back(c.kind + " case " + std::to_string(index) + " (" + what + "): " + command +
                           ": the message does not name " + place + ": " + r.err.substr(0, 300));
  if (r.err.size() > 5000)
    c.violations.push_back(c.kind + " case " + std::to_string(index) + " (" + what + "): " + command +
                           ": a message of " + std::to_string(r.err.size()) + " bytes");
}

}  // namespace

TEST_CASE("hostile families of issue 33 are refused with exit 2, naming the file or option", "[fuzz]") {
  Campaign c("hostile33", ".in");
  Mutator m(c.seed);
  const int cases = fuzz_cases(kSanitized ? 2 : 4);
  const fs::path err = c.dir / "err.txt";
  int index = 0;
  const std::string crossed = slurp(source_dir() / "tests/data/analysis/likert_crossed.csv");
  const std::string first_row = "p1,s1,baseline,1,2\n";
  REQUIRE(crossed.find(first_row) != std::string::npos);
  // Ratings outside the range of a double (std::stod threw a bare "stod"), through analyze clmm.
  for (int k = 0; k < cases; ++k, ++index) {
    const std::string exponent = std::to_string(309 + m.below(5000));
    const std::string value = (m.below(2) ? "-1e" : "1e") + std::string(m.below(2) ? "-" : "") + exponent;
    std::string text = crossed;
    text.replace(text.find(first_row), first_row.size(), "p1,s1,baseline,1," + value + "\n");
    write_file(c.input_path(index), text);
    const std::string in = c.input_path(index).string();
    record_named_refusal(c, index, "rating " + value, "`crowdlab analyze clmm`",
                         run_crowdlab_limited({"analyze", "clmm", "--csv", in, "--formula",
                                               "rating ~ method + (1 | participant)"},
                                              run_limit_s(), err),
                         in);
  }
  // Formulas crossing many columns the file lacks (a bad_alloc after 67 s), through analyze lmm.
  for (int k = 0; k < cases; ++k, ++index) {
    const std::size_t n = 11 + m.below(40);
    std::string formula = "rating ~ ";
    for (std::size_t i = 0; i < n; ++i) formula += (i ? "*" : "") + std::string("x") + std::to_string(i);
    write_file(c.input_path(index), crossed);
    const std::string in = c.input_path(index).string();
    record_named_refusal(
        c, index, std::to_string(n) + " crossed missing columns", "`crowdlab analyze lmm`",
        run_crowdlab_limited({"analyze", "lmm", "--csv", in, "--formula", formula + " + (1 | participant)"},
                             run_limit_s(), err),
        in);
  }
  // Option values off their range (a 300-digit limit was printed).
  for (int k = 0; k < cases; ++k, ++index) {
    const std::string value = m.below(2) ? "0" : "-" + std::to_string(1 + m.below(1000000));
    write_file(c.input_path(index), crossed);
    record_named_refusal(
        c, index, "--max-levels " + value, "`crowdlab analyze anova --max-levels`",
        run_crowdlab_limited({"analyze", "anova", "--csv", c.input_path(index).string(), "--dv", "rating",
                              "--subject", "participant", "--within", "method", "--max-levels", value},
                             run_limit_s(), err),
        "--max-levels: must");
  }
  // Flow crowds far past the character limit (5 GB at 180 s before), through validate.
  const std::string flow_spec =
      "crowdlab: 1\nname: f\nseed: 1\nscenario: {type: flow_b, area: {width_m: W, depth_m: W}}\n"
      "factors: {density: [D]}\nprotocol:\n  type: likert\n  questions: [{id: Q1, text: x}]\n";
  for (int k = 0; k < cases; ++k, ++index) {
    const std::string width = std::to_string(200 + m.below(800)), density = std::to_string(1 + m.below(10));
    std::string text = flow_spec;
    text.replace(text.find("W"), 1, width);
    text.replace(text.find("W"), 1, width);
    text.replace(text.find("[D]"), 3, "[" + density + "]");
    write_file(c.input_path(index), text);
    const std::string in = c.input_path(index).string();
    record_named_refusal(c, index, "flow_b " + width + " m at density " + density, "`crowdlab validate`",
                         run_crowdlab_limited({"validate", in}, run_limit_s(), err), in);
  }
  // Manifold crowds on large OBJ surfaces (an int overflow, then "agents: must be >= 1").
  for (int k = 0; k < cases; ++k, ++index) {
    const double half = 100.0 + static_cast<double>(m.below(100000));
    const fs::path obj = c.dir / ("surface-" + std::to_string(index) + ".obj");
    const std::string h = std::to_string(half);
    write_file(obj, "v -" + h + " 0 -" + h + "\nv " + h + " 0 -" + h + "\nv " + h + " 0 " + h + "\nv -" + h +
                        " 0 " + h + "\nf 1 2 3\nf 1 3 4\n");
    write_file(c.input_path(index),
               "crowdlab: 1\nname: m\nseed: 1\nscenario: {type: manifold, mesh: " + obj.string() +
                   "}\ncrowd: {model: orca}\nfactors: {density: [2]}\n"
                   "protocol:\n  type: likert\n  questions: [{id: Q1, text: x}]\n");
    const std::string in = c.input_path(index).string();
    record_named_refusal(c, index, "manifold of half-width " + h + " m", "`crowdlab validate`",
                         run_crowdlab_limited({"validate", in}, run_limit_s(), err), in);
  }
  // BVH clips whose first token is raw binary (echoed whole before); a byte-order mark alone is accepted.
  for (int k = 0; k < cases; ++k, ++index) {
    std::string junk(1000 + m.below(100000), '\0');
    for (char& ch : junk) ch = static_cast<char>(1 + m.below(31));
    write_file(c.input_path(index), "\xEF\xBB\xBF" + junk + "\nHIERARCHY\n");
    const fs::path path = c.input_path(index);
    const auto read = [&] { return exit_code_of([&] { (void)import_bvh(path.string()); }); };
    record_named_refusal(c, index, std::to_string(junk.size()) + " binary bytes", "import_bvh",
                         run_limited(read, run_limit_s(), err), path.string());
  }
  // Specs naming a dance clip or a glTF character of random bytes (validate only checked that the file
  // existed; run refused it later without the spec's line), through validate.
  for (int k = 0; k < cases; ++k, ++index) {
    const bool character = m.below(2) == 1;
    std::string junk(10 + m.below(5000), '\0');
    for (char& ch : junk) ch = static_cast<char>(m.below(256));
    const fs::path file = c.dir / ("asset-" + std::to_string(index) + (character ? ".glb" : ".bvh"));
    write_file(file, junk);
    write_file(
        c.input_path(index),
        "crowdlab: 1\nname: a\nseed: 1\nfactors: {characters: [2]}\n" +
            std::string(character ? "render: {characters: [" : "animation: {motion: clips, dance_clips: [") +
            file.string() + "]}\nprotocol:\n  type: likert\n  questions: [{id: Q1, text: x}]\n");
    const std::string in = c.input_path(index).string();
    record_named_refusal(
        c, index,
        std::to_string(junk.size()) + " random bytes as a " + (character ? "character" : "dance clip"),
        "`crowdlab validate`", run_crowdlab_limited({"validate", in}, run_limit_s(), err), in);
  }
  // Reports over their participant-item limit (2,000 participants ran for minutes), through analyze report.
  for (int k = 0; k < cases; ++k, ++index) {
    const fs::path study = c.dir / ("study-" + std::to_string(index));
    fs::create_directories(study);
    const std::size_t participants = 2 + m.below(30);
    std::string rows =
        "participant,session,trial,stimulus,density,viewpoint,method,question,response,reverse_coded,"
        "practice\n";
    for (std::size_t p = 1; p <= participants; ++p)
      for (const char* method : {"baseline", "ours"})
        for (int q = 1; q <= 6; ++q) {
          const int r = 1 + static_cast<int>(m.below(6));  // Q2, Q4 and Q6 are reverse-keyed in the demo
          rows += std::to_string(p) + ",1,1,s_" + method + ",3.33,V1," + method + ",Q" + std::to_string(q) +
                  "," + std::to_string(r) + "," + std::to_string(q % 2 ? r : 7 - r) + ",0\n";
        }
    write_file(study / "responses.csv", rows);
    const std::string limit = std::to_string(1 + m.below(participants * 6 - 1));  // below participants x 6
    record_named_refusal(c, index,
                         std::to_string(participants) + " participants at --max-participant-items " + limit,
                         "`crowdlab analyze report`",
                         run_crowdlab_limited({"analyze", "report", study.string(), "--spec",
                                               (source_dir() / "experiments" / "demo.yaml").string(), "--out",
                                               (study / "out").string(), "--max-participant-items", limit},
                                              run_limit_s(), err),
                         "--max-participant-items");
  }
  c.report();
}

TEST_CASE("the fuzz harness reports a signal, a hang, memory over the cap and a silent exit 2", "[fuzz]") {
  // Without this the campaigns above could pass by never seeing a failure.
  const fs::path err = scratch_dir("fuzz_harness") / "err.txt";
  const auto violation = [&](const std::function<int()>& body, double limit_s = 20.0) {
    return run_limited(body, limit_s, err).violation();
  };
  CHECK_THAT(violation([] { return 0; }), Catch::Equals(""));
  CHECK_THAT(violation([] {
               std::fprintf(stderr, "crowdlab: error: f.yaml:1:1: bad\n");
               return 2;
             }),
             Catch::Equals(""));
  CHECK_THAT(violation([] { return 2; }), Catch::Contains("without an error message"));
  CHECK_THAT(violation([] { return 1; }), Catch::Contains("exited with code 1"));
  CHECK_THAT(violation([] {
               raise(SIGSEGV);
               return 0;
             }),
             Catch::Contains("signal 11"));
  CHECK_THAT(violation(
                 [] {
                   pause();
                   return 0;
                 },
                 0.5),
             Catch::Contains("time limit"));
  // Touching 1.5 GB: over the resident cap (in Release RLIMIT_AS may stop it first, as std::bad_alloc).
  // A long time limit: a VM whose host hands out fresh pages lazily touches them at ~60 MB/s (measured
  // on the development machine in session 16: 1.5 GB in 25 s), and the cap must be reached first.
  const std::string memory = violation(
      [] {
        std::vector<char> big(std::size_t{1536} << 20);
        for (std::size_t i = 0; i < big.size(); i += 4096) big[i] = 1;
        return big[4096] == 1 ? 0 : 3;
      },
      120.0);
  CHECK_THAT(memory, Catch::Contains("memory cap") || Catch::Contains("exited with code 1") ||
                         Catch::Contains("signal"));
}

}  // namespace test_fuzz_inputs
