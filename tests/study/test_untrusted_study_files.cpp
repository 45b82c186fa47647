// Issue 32: study files that a participant's browser or an edit produced are untrusted. Deep JSON is
// refused with the file and the byte (it overflowed the stack), an import never replaces a participant's
// files, a resumed session never appends through a link, and FIFOs are refused without blocking.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "framework/core/error.hpp"
#include "study_ui/run_session.hpp"
#include "study_ui/scripted_presenter.hpp"
#include "study_ui/web_export.hpp"
#include "study_ui/web_import.hpp"
#include "tests/study/web_fixture.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_untrusted_study_files {

using namespace crowdlab;
using namespace crowdlab::study;
namespace fs = std::filesystem;
using crowdlab::test::slurp;
using namespace crowdlab::test::web;

namespace {

struct WebStudy {
  fs::path dir;
  StimulusManifest m;
  ExperimentSpec spec = test::likert_spec();
  nlohmann::json good;
  WebImportOptions opt;

  explicit WebStudy(const std::string& name)
      : dir(test::scratch_dir(name)),
        m(test::make_stimuli(dir / "stimuli", {{"density", {"2.22", "6.66"}}}, 1)),
        opt{(dir / "out").string(), (dir / "stimuli").string()} {
    const auto answers = scripted_answers(m, resolve_questions(spec.protocol));
    good = web_dump(web_timeline(spec, m, "sha", numbered_participant_ids(2)), "P01", answers);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  }
};

std::string nested(std::size_t depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

}  // namespace

TEST_CASE("import-web refuses JSON nested deeper than its limit with the file and byte, never crashing",
          "[study]") {
  WebStudy w("untrusted-deep-web");
  // The records sit 3 levels deep ({"records": [{...}]}), so level 33 is the array's 30th bracket.
  // 300,000 levels overflowed the stack (SIGSEGV); 100,000 ran out of memory. In one JSON document, in
  // a JSON line.
  for (const char* key : {"spec_hash", "answers", "stimulus"}) {
    CAPTURE(key);
    std::string text = w.good.dump();
    const std::string field = "\"" + std::string(key) + "\":";
    const size_t at = text.find(field);
    REQUIRE(at != std::string::npos);
    const size_t value = at + field.size();
    text.insert(value, nested(300000) + ",\"x\":");  // the key's value is now the deep array
    const std::string file = w.write(std::string("deep-") + key + ".json", text);
    CHECK_THROWS_WITH(import_web(w.spec, w.m, {file}, w.opt),
                      Catch::Contains(file) &&
                          Catch::Contains("more than 32 levels deep at byte " + std::to_string(value + 29)));
  }
  const std::string lines =
      w.write("deep.jsonl", w.good["records"][0].dump() + "\n{\"video\": " + nested(100000) + "}\n");
  CHECK_THROWS_WITH(import_web(w.spec, w.m, {lines}, w.opt),
                    Catch::Contains(lines + ":2") && Catch::Contains("levels deep"));
  CHECK_FALSE(fs::exists(w.dir / "out" / "P01.csv"));
}

TEST_CASE("import-web refuses a result file over --max-file-mb and a FIFO before reading either", "[study]") {
  WebStudy w("untrusted-size-web");
  const std::string file = w.write("big.json", w.good.dump());
  WebImportOptions small = w.opt;
  small.max_file_bytes = 100;
  CHECK_THROWS_WITH(import_web(w.spec, w.m, {file}, small), Catch::Contains(file) &&
                                                                Catch::Contains("limit of 100 bytes") &&
                                                                Catch::Contains("--max-file-mb"));
  const fs::path fifo = w.dir / "results.json";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(import_web(w.spec, w.m, {fifo.string()}, w.opt),
                    Catch::Contains(fifo.string()) && Catch::Contains("FIFO"));
  fs::create_directories(w.dir / "results");
  fs::rename(fifo, w.dir / "results" / "results.json");
  CHECK_THROWS_WITH(import_web(w.spec, w.m, {(w.dir / "results").string()}, w.opt), Catch::Contains("FIFO"));
}

TEST_CASE("import-web never replaces an existing participant's files", "[study]") {
  WebStudy w("untrusted-replace-web");
  const std::string file = w.write("P01.json", w.good.dump());
  fs::create_directories(w.dir / "out");
  // An earlier session's metadata without its CSV (issue 32: replaced, exit 0).
  std::ofstream(w.dir / "out" / "P01.json") << "{\"participant\": \"P01\", \"source\": \"lab\"}\n";
  CHECK_THROWS_WITH(import_web(w.spec, w.m, {file}, w.opt),
                    Catch::Contains((w.dir / "out" / "P01.json").string()) && Catch::Contains(file + ":1") &&
                        Catch::Contains("refusing to overwrite"));
  CHECK(slurp(w.dir / "out" / "P01.json") == "{\"participant\": \"P01\", \"source\": \"lab\"}\n");
  CHECK_FALSE(fs::exists(w.dir / "out" / "P01.csv"));
  // A participant file that is a link to elsewhere is refused, the target untouched.
  fs::remove(w.dir / "out" / "P01.json");
  std::ofstream(w.dir / "elsewhere.csv") << "keep";
  fs::create_symlink(w.dir / "elsewhere.csv", w.dir / "out" / "P01.csv");
  CHECK_THROWS_WITH(import_web(w.spec, w.m, {file}, w.opt), Catch::Contains("symbolic link"));
  CHECK(slurp(w.dir / "elsewhere.csv") == "keep");
  // The same records again: byte for byte the same CSV, nothing rewritten.
  fs::remove(w.dir / "out" / "P01.csv");
  REQUIRE(import_web(w.spec, w.m, {file}, w.opt).participants == 1);
  const auto json_time = fs::last_write_time(w.dir / "out" / "P01.json");
  CHECK(import_web(w.spec, w.m, {file}, w.opt).already_imported == 1);
  CHECK(fs::last_write_time(w.dir / "out" / "P01.json") == json_time);
}

namespace {

struct Session {
  fs::path dir;
  StimulusManifest m;
  ExperimentSpec spec = test::likert_spec();
  fs::path script;

  explicit Session(const std::string& name)
      : dir(test::scratch_dir(name)),
        m(test::make_stimuli(dir / "stimuli", {{"density", {"2.22", "6.66"}}}, 1)) {
    script = write_script(dir / "script.csv", scripted_answers(m, resolve_questions(spec.protocol)),
                          resolve_questions(spec.protocol));
  }
  SessionResult run(bool resume) const {
    ScriptedPresenter presenter(script.string(), 0);
    SessionOptions opt{"P01", (dir / "stimuli").string(), (dir / "out").string(), resume, "scripted", true,
                       false};
    return run_session(spec, m, opt, presenter);
  }
};

}  // namespace

TEST_CASE("study --resume never appends through a linked log or reads deep or ill-typed metadata",
          "[study]") {
  Session s("untrusted-resume");
  const SessionResult first = s.run(false);
  const std::string log = slurp(first.csv_path);
  // P01.csv a link to a file outside --out (issue 32: appended through the link).
  const fs::path outside = s.dir / "outside.csv";
  fs::rename(first.csv_path, outside);
  fs::create_symlink(outside, first.csv_path);
  CHECK_THROWS_WITH(s.run(true), Catch::Contains(first.csv_path) && Catch::Contains("symbolic link"));
  CHECK(slurp(outside) == log);
  fs::remove(first.csv_path);
  fs::rename(outside, first.csv_path);
  const std::string meta = slurp(first.json_path);
  // Session metadata nested 300,000 deep, and `"runs": 5` (a JSON type error, exit 1, issue 33).
  std::ofstream(first.json_path) << "{\"runs\": " << nested(300000) << "}";
  CHECK_THROWS_WITH(s.run(true),
                    Catch::Contains(first.json_path) && Catch::Contains("levels deep at byte 72"));
  std::ofstream(first.json_path) << "{\"participant\": \"P01\", \"runs\": 5}";
  CHECK_THROWS_WITH(s.run(true), Catch::Contains(first.json_path) && Catch::Contains("runs"));
  std::ofstream(first.json_path) << meta;
  CHECK(s.run(true).trials_done_now == 0);
}

TEST_CASE("a resumed log whose last session is the largest int is refused, not wrapped", "[study]") {
  Session s("untrusted-session-overflow");
  const SessionResult first = s.run(false);
  std::string log = slurp(first.csv_path);
  // Every row's session cell (the second column) set to INT_MAX.
  std::string edited;
  for (size_t pos = 0; pos < log.size();) {
    const size_t end = log.find('\n', pos) + 1;
    std::string row = log.substr(pos, end - pos);
    if (pos > 0) {
      const size_t a = row.find(','), b = row.find(',', a + 1);
      row.replace(a + 1, b - a - 1, std::to_string(std::numeric_limits<int>::max()));
    }
    edited += row;
    pos = end;
  }
  std::ofstream(first.csv_path, std::ios::binary) << edited;
  CHECK_THROWS_WITH(s.run(true), Catch::Contains(first.csv_path) && Catch::Contains("2147483647"));
}

TEST_CASE("import-web refuses integers beyond int's range instead of truncating them (issue 33)", "[study]") {
  WebStudy w("untrusted-int-web");
  const struct {
    const char* name;
    std::function<void(nlohmann::json&)> edit;
    const char* key;
  } cases[] = {{"response", [](nlohmann::json& r) { r["answers"][0]["response"] = 4294967299ull; },
                "answers[0].response"},
               {"trial", [](nlohmann::json& r) { r["trial"] = 4294967298ull; }, "trial"},
               {"session", [](nlohmann::json& r) { r["session"] = 4294967297ull; }, "session"},
               {"negative", [](nlohmann::json& r) { r["session"] = -4294967295ll; }, "session"}};
  for (const auto& c : cases) {
    CAPTURE(c.name);
    nlohmann::json dump = w.good;
    c.edit(dump["records"][0]);
    const std::string file = w.write(std::string(c.name) + ".json", dump.dump());
    CHECK_THROWS_WITH(import_web(w.spec, w.m, {file}, w.opt),
                      Catch::Contains(file + ":1: " + c.key) && Catch::Contains("4294967"));
  }
  CHECK_FALSE(fs::exists(w.dir / "out" / "P01.csv"));
}

}  // namespace test_untrusted_study_files
