// import-web of jsPsych's CSV data (jsPsych.data.get().csv()): a folder of CSVs imports like JSON, and
// malformed CSVs are refused with the file, line and key, exit code 2 from the command line.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "framework/core/error.hpp"
#include "study_ui/web_import.hpp"
#include "tests/study/web_fixture.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_web_csv {

using namespace crowdlab;
using namespace crowdlab::study;
using namespace crowdlab::test::web;
using crowdlab::test::slurp;

TEST_CASE("import-web reads jsPsych CSV data, malformed CSVs are refused with file, line and key",
          "[study]") {
  const auto dir = test::scratch_dir("web-csv");
  const auto m = test::make_stimuli(dir / "stimuli",
                                    {{"density", {"2.22", "6.66"}}, {"method", {"baseline", "ours"}}}, 1);
  const ExperimentSpec spec = test::likert_spec();
  const auto qs = resolve_questions(spec.protocol);
  const nlohmann::json timeline = web_timeline(spec, m, "sha", numbered_participant_ids(2));
  const nlohmann::json good = web_dump(timeline, "P01", scripted_answers(m, qs));
  const WebImportOptions opt{(dir / "out").string(), (dir / "stimuli").string()};
  // Rows: header (line 1), full screen (2), then per record its row and a two-line text screen, so
  // record k is on line 3 + 3k.
  const std::string text = jspsych_csv(jspsych_trials(good));
  auto refused = [&](const std::string& name, const std::string& csv, const std::string& where,
                     const std::string& words) {
    const fs::path file = dir / (name + ".csv");
    std::ofstream(file, std::ios::binary) << csv;
    CAPTURE(name, where, words);
    try {
      import_web(spec, m, {file.string()}, opt);
      FAIL("accepted " + name);
    } catch (const InputError& e) {
      CAPTURE(e.what());
      CHECK(std::string(e.what()).find(file.string() + where) != std::string::npos);
      CHECK(std::string(e.what()).find(words) != std::string::npos);
    }
    CHECK_FALSE(fs::exists(dir / "out" / "P01.csv"));  // nothing written
  };
  auto replace = [&](std::string csv, const std::string& from, const std::string& to) {
    const size_t at = csv.find(from);
    REQUIRE(at != std::string::npos);
    return csv.replace(at, from.size(), to);
  };
  refused("no-column", replace(text, "\"crowdlab_record\"", "\"record\""),
          ":1: crowdlab_record: ", "not jsPsych data of a crowdlab web study");
  refused("open-quote", text + "\"812\",\"fullscreen\r\n", ":", "unterminated quoted field");
  refused("ragged", replace(text, "\r\n\"812\"", "\r\n\"1\",\"812\""), ":2: ", "row has");
  const std::string cell1 = jspsych_quoted(nlohmann::ordered_json::parse(good["records"][1].dump()).dump());
  refused("torn-json", replace(text, cell1, "\"{\"\"format\"\": \"\"crowdlab-web-da\""),
          ":6: crowdlab_record: ", "not valid JSON");
  refused("not-object", replace(text, cell1, "\"[1, 2]\""),
          ":6: crowdlab_record: ", "expected a trial record");
  // The checks of the records themselves name the CSV row's line, as for JSON lines.
  nlohmann::json other_spec = good;
  other_spec["records"][1]["spec_hash"] = "other";
  refused("spec", jspsych_csv(jspsych_trials(other_spec)), ":6: spec_hash: ", "another spec");
  nlohmann::json bad_answer = good;
  bad_answer["records"][2]["answers"][3]["response"] = 9;
  refused("range", jspsych_csv(jspsych_trials(bad_answer)), ":9: answers[3].response: ", "invalid response");
  // Bad input ends the command with exit code 2, the message on stderr.
  const std::string exe = test::crowdlab_exe().string();
  const std::string cmd = exe + " import-web " + (dir / "open-quote.csv").string() + " --spec " +
                          (test::source_dir() / "experiments" / "demo.yaml").string() + " --stimuli " +
                          (dir / "stimuli").string() + " --out " + (dir / "cli-out").string() + " > " +
                          (dir / "cli.log").string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  CHECK((WIFEXITED(rc) ? WEXITSTATUS(rc) : -1) == 2);
  CHECK_THAT(slurp(dir / "cli.log"), Catch::Contains("open-quote.csv:") && Catch::Contains("unterminated"));

  // A folder of CSVs (the participant's data saved twice: identical rows merge) imports like JSON.
  fs::create_directories(dir / "folder");
  std::ofstream(dir / "folder" / "P01_session.csv", std::ios::binary) << text;
  std::ofstream(dir / "folder" / "P01_again.CSV", std::ios::binary) << text;
  const WebImportResult r = import_web(spec, m, {(dir / "folder").string()}, opt);
  CHECK(r.files == 2);
  CHECK(r.complete == 1);
  CHECK(r.duplicates_merged == static_cast<int>(good["records"].size()));
  write_json(dir / "P01.json", good);
  CHECK(import_web(spec, m, {(dir / "P01.json").string()}, {(dir / "out-json").string(), opt.stimuli_dir})
            .complete == 1);
  CHECK(slurp(dir / "out" / "P01.csv") == slurp(dir / "out-json" / "P01.csv"));
}

}  // namespace test_web_csv
