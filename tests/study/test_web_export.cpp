// The web study's files (export-web / import-web), without a browser: trial orders equal to the native
// session's, the import of web records into native tidy CSVs, refusal of bad input, the JATOS archive's
// structure, and the npm packages pinned for the page (exactly those it loads). The page in headless
// Chromium is test_web_browser.cpp.

#include <zip.h>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "stimuli/video_encoder.hpp"
#include "study_ui/run_session.hpp"
#include "study_ui/scripted_presenter.hpp"
#include "study_ui/web_export.hpp"
#include "study_ui/web_import.hpp"
#include "tests/study/web_fixture.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_web_export {

using namespace crowdlab;
using namespace crowdlab::study;
namespace fs = std::filesystem;
using crowdlab::test::slurp;
using namespace crowdlab::test::web;
using crowdlab::test::source_dir;

namespace {

/// The entries of a ZIP archive (name -> bytes), read back with libzip; also checks that each entry is
/// stored (not compressed) and carries the fixed 1980-01-01 time.
std::vector<std::pair<std::string, std::string>> zip_entries(const std::string& path) {
  int code = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &code);
  REQUIRE(z != nullptr);
  std::vector<std::pair<std::string, std::string>> out;
  for (zip_int64_t i = 0; i < zip_get_num_entries(z, 0); ++i) {
    zip_stat_t st;
    REQUIRE(zip_stat_index(z, static_cast<zip_uint64_t>(i), 0, &st) == 0);
    CHECK(st.comp_method == ZIP_CM_STORE);
    std::string data(st.size, '\0');
    zip_file_t* f = zip_fopen_index(z, static_cast<zip_uint64_t>(i), 0);
    REQUIRE(f != nullptr);
    CHECK(zip_fread(f, data.data(), st.size) == static_cast<zip_int64_t>(st.size));
    zip_fclose(f);
    out.emplace_back(st.name, data);
  }
  zip_discard(z);
  return out;
}

/// Empty stand-ins for the jsPsych files, so that export_web runs without npm.
fs::path fake_node_modules(const fs::path& dir) {
  for (const auto& [from, to] : jspsych_bundle_files()) {
    fs::create_directories((dir / from).parent_path());
    std::ofstream(dir / from) << "// stand-in\n";
  }
  return dir;
}

}  // namespace

TEST_CASE("web trial orders equal the native session's for embedded ids, other ids map by FNV-1a",
          "[study]") {
  const auto dir = test::scratch_dir("web-order");
  const auto m = test::make_stimuli(
      dir / "stimuli", {{"density", {"2.22", "6.66", "9.99"}}, {"method", {"baseline", "ours"}}}, 2);
  const auto qs = resolve_questions(test::likert_spec().protocol);
  const auto script = write_script(dir / "script.csv", scripted_answers(m, qs), qs);
  const std::vector<std::string> ids = {"P01", "P02", "P03", "P17", "lab_A"};
  for (const BlockOrder block_order : {BlockOrder::random, BlockOrder::latin_square, BlockOrder::fixed}) {
    const ExperimentSpec spec = blocked_spec(block_order);
    const std::string order(kind_name(block_order));
    const nlohmann::json timeline = web_timeline(spec, m, "sha", ids);
    for (const std::string& id : ids) {
      // The native session's sequence of (trial, stimulus, block) from its P.csv, one per trial.
      const CsvTable t =
          read_csv(native_csv(spec, m, dir / "stimuli", script, dir / ("native-" + order), id));
      std::vector<std::tuple<int, std::string, std::string>> native, web;
      for (size_t r = 0; r < t.rows.size(); r += qs.size())
        native.emplace_back(std::stoi(t.cell(r, t.column("trial"))), t.cell(r, t.column("stimulus")),
                            t.cell(r, t.column("block")));
      for (const auto& w : timeline["orders"][id]) web.emplace_back(w["trial"], w["stimulus"], w["block"]);
      CAPTURE(order, id);
      CHECK(web == native);
    }
    // Orders differ between participants (the shuffles are per participant).
    CHECK(timeline["orders"]["P01"] != timeline["orders"]["P02"]);
  }
  // FNV-1a 32 test vectors (http://www.isthe.com/chongo/tech/comp/fnv/) and the slot rule.
  CHECK(fnv1a32("") == 0x811c9dc5u);
  CHECK(fnv1a32("a") == 0xe40c292cu);
  CHECK(fnv1a32("foobar") == 0xbf9cf968u);
  CHECK(web_order_participant("P02", ids) == "P02");
  CHECK(web_order_participant("5f2a0c9e1b", ids) == ids[fnv1a32("5f2a0c9e1b") % ids.size()]);
  CHECK(numbered_participant_ids(3) == std::vector<std::string>{"P01", "P02", "P03"});
  CHECK(numbered_participant_ids(120)[119] == "P120");
}

TEST_CASE("import-web of web records equals the native scripted session's table", "[study]") {
  const auto dir = test::scratch_dir("web-import");
  const auto m = test::make_stimuli(dir / "stimuli",
                                    {{"density", {"2.22", "6.66"}}, {"method", {"baseline", "ours"}}}, 2);
  for (const bool afc : {false, true}) {
    const ExperimentSpec spec = afc ? test::afc_spec() : blocked_spec(BlockOrder::latin_square);
    const auto qs = resolve_questions(spec.protocol);
    const auto answers = scripted_answers(m, qs);
    const fs::path sub = dir / (afc ? "afc" : "likert");
    const auto script = write_script(sub.string() + "-script.csv", answers, qs);
    const nlohmann::json timeline = web_timeline(spec, m, "sha", numbered_participant_ids(4));
    for (const std::string id : {"P03", "PROLIFIC5f2a"}) {
      write_json(sub.string() + "-" + id + ".json", web_dump(timeline, id, answers));
      const WebImportResult r = import_web(spec, m, {sub.string() + "-" + id + ".json"},
                                           {(sub / "web").string(), (dir / "stimuli").string()});
      CHECK(r.participants == 1);
      CHECK(r.complete == 1);
      // The native session of the id whose order the web participant ran, renamed.
      const std::string order_of = web_order_participant(id, timeline["order_ids"]);
      const auto native = native_csv(spec, m, dir / "stimuli", script, sub / ("native-" + id), order_of);
      auto expected = comparable_rows(native, {"timestamp", "participant"});
      CAPTURE(afc, id);
      CHECK(comparable_rows((sub / "web" / (id + ".csv")).string(), {"timestamp", "participant"}) ==
            expected);
      CHECK(read_csv((sub / "web" / (id + ".csv")).string()).header == read_csv(native).header);
      const auto meta = nlohmann::json::parse(slurp((sub / "web" / (id + ".json")).string()));
      CHECK(meta["status"] == "complete");
      CHECK(meta["order_of"] == order_of);
      // The same records in jsPsych's CSV data (jsPsych.data.get().csv()) give the same table.
      const fs::path csv = sub.string() + "-" + id + "-jspsych.csv";
      std::ofstream(csv, std::ios::binary) << jspsych_csv(jspsych_trials(web_dump(timeline, id, answers)));
      CHECK(import_web(spec, m, {csv.string()}, {(sub / "web-csv").string(), (dir / "stimuli").string()})
                .complete == 1);
      CHECK(slurp(sub / "web-csv" / (id + ".csv")) == slurp(sub / "web" / (id + ".csv")));
    }
  }
}

TEST_CASE("import-web refuses foreign specs and stimuli, wrong orders, conflicting duplicates and bad files",
          "[study]") {
  const auto dir = test::scratch_dir("web-bad");
  const auto m = test::make_stimuli(dir / "stimuli",
                                    {{"density", {"2.22", "6.66"}}, {"method", {"baseline", "ours"}}}, 1);
  const ExperimentSpec spec = test::likert_spec();
  const auto qs = resolve_questions(spec.protocol);
  const auto answers = scripted_answers(m, qs);
  const nlohmann::json timeline = web_timeline(spec, m, "sha", numbered_participant_ids(2));
  const nlohmann::json good = web_dump(timeline, "P01", answers);
  const WebImportOptions opt{(dir / "out").string(), (dir / "stimuli").string()};
  auto expect_refused = [&](nlohmann::json dump, const std::string& name, const std::string& words) {
    const fs::path file = dir / (name + ".json");
    write_json(file, dump);
    CAPTURE(name);
    try {
      import_web(spec, m, {file.string()}, opt);
      FAIL("accepted " + name);
    } catch (const InputError& e) {
      const std::string what = e.what();
      CHECK(what.find(file.string()) != std::string::npos);
      CHECK(what.find(words) != std::string::npos);
    }
    CHECK_FALSE(fs::exists(dir / "out" / "P01.csv"));  // nothing written
  };
  auto with = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json d = good;
    edit(d);
    return d;
  };
  expect_refused(with([](nlohmann::json& d) { d["records"][1]["spec_hash"] = "other"; }), "spec",
                 "another spec");
  expect_refused(with([](nlohmann::json& d) { d["records"][2]["stimulus_sha256"] = "00"; }), "sha",
                 "not the manifest's");
  expect_refused(
      with([](nlohmann::json& d) { std::swap(d["records"][1]["stimulus"], d["records"][2]["stimulus"]); }),
      "order", "the order of P01");
  expect_refused(with([](nlohmann::json& d) { d["records"][0]["answers"][3]["response"] = 7; }), "range",
                 "invalid response");
  expect_refused(with([](nlohmann::json& d) { d["records"][0]["answers"].erase(5); }), "count",
                 "expected 6 answers");
  expect_refused(with([](nlohmann::json& d) {
                   auto copy = d["records"][2];
                   copy["answers"][0]["response"] = copy["answers"][0]["response"].get<int>() % 6 + 1;
                   d["records"].push_back(copy);
                 }),
                 "conflict", "differently");
  expect_refused(with([](nlohmann::json& d) { d["format"] = "something"; }), "format",
                 "not crowdlab web study data");
  {
    std::ofstream(dir / "torn.jsonl")
        << good["records"][0].dump() << "\n{\"format\": \"crowdlab-web-data\", \"tri\n";
    CHECK_THROWS_WITH(import_web(spec, m, {(dir / "torn.jsonl").string()}, opt),
                      Catch::Contains("torn.jsonl:2") && Catch::Contains("not valid JSON"));
  }
  // Identical duplicates (a JATOS append and the download of the same session) merge.
  std::ofstream lines(dir / "jatos.txt");
  for (const auto& r : good["records"]) lines << r.dump() << "\n";
  lines.close();
  write_json(dir / "download.json", good);
  const WebImportResult r =
      import_web(spec, m, {(dir / "jatos.txt").string(), (dir / "download.json").string()}, opt);
  CHECK(r.duplicates_merged == static_cast<int>(good["records"].size()));
  CHECK(r.complete == 1);
  // jsPsych's own data (jsPsych.data.get().json()): the records ride on the trials as crowdlab_record.
  nlohmann::json jspsych = nlohmann::json::array({{{"trial_type", "fullscreen"}, {"rt", 812}}});
  for (const auto& rec : good["records"])
    jspsych.push_back({{"trial_type", "survey-likert"}, {"crowdlab_record", rec}});
  write_json(dir / "jspsych.json", jspsych);
  const WebImportOptions other{(dir / "out-jspsych").string(), (dir / "stimuli").string()};
  CHECK(import_web(spec, m, {(dir / "jspsych.json").string()}, other).complete == 1);
  CHECK(slurp(dir / "out-jspsych" / "P01.csv") == slurp(dir / "out" / "P01.csv"));
  // Importing again is a no-op; different answers for an imported participant are refused.
  CHECK(import_web(spec, m, {(dir / "download.json").string()}, opt).already_imported == 1);
  nlohmann::json changed = good;
  changed["records"][0]["answers"][0]["rt_ms"] = 1.5;
  write_json(dir / "changed.json", changed);
  CHECK_THROWS_WITH(import_web(spec, m, {(dir / "changed.json").string()}, opt),
                    Catch::Contains("refusing to overwrite"));
}

TEST_CASE(
    "import-web imports every valid participant, reports the others by file and reason, refuses case "
    "clashes, and writes nothing for a refused input",
    "[study]") {
  const auto dir = test::scratch_dir("web-partial");
  const auto m = test::make_stimuli(dir / "stimuli", {{"density", {"2.22", "6.66"}}}, 1);
  const ExperimentSpec spec = test::likert_spec();
  const auto qs = resolve_questions(spec.protocol);
  const auto answers = scripted_answers(m, qs);
  const nlohmann::json timeline = web_timeline(spec, m, "sha", numbered_participant_ids(2));
  fs::create_directories(dir / "results");
  write_json(dir / "results" / "P01.json", web_dump(timeline, "P01", answers));
  write_json(dir / "results" / "P02.json", web_dump(timeline, "P02", answers));
  write_json(dir / "results" / "_P07.json", web_dump(timeline, "_P07", answers));  // finding 1
  const WebImportOptions opt{(dir / "out").string(), (dir / "stimuli").string()};
  // --strict: one bad file refuses everything, and nothing is written.
  WebImportOptions strict = opt;
  strict.strict = true;
  CHECK_THROWS_WITH(import_web(spec, m, {(dir / "results").string()}, strict),
                    Catch::Contains("_P07.json") && Catch::Contains("starting with a letter or digit"));
  CHECK_FALSE(fs::exists(dir / "out"));
  // Without: the bad file blocks nobody else; it is reported by file and reason.
  const WebImportResult r = import_web(spec, m, {(dir / "results").string()}, opt);
  CHECK(r.participants == 2);
  CHECK(r.complete == 2);
  REQUIRE(r.problems.size() == 1);
  CHECK(r.problems[0].find((dir / "results" / "_P07.json").string()) != std::string::npos);
  CHECK(r.problems[0].find("starting with a letter or digit") != std::string::npos);
  CHECK(fs::exists(dir / "out" / "P01.csv"));
  CHECK_FALSE(fs::exists(dir / "out" / "_P07.csv"));
  // Case clashes (finding 4), as `crowdlab study` refuses them: with a file in --out, and within the
  // results (both refused: a human decides).
  write_json(dir / "p01.json", web_dump(timeline, "p01", answers));
  CHECK_THROWS_WITH(import_web(spec, m, {(dir / "p01.json").string()}, opt),
                    Catch::Contains("clashes with 'P01'") && Catch::Contains("nothing written"));
  CHECK_FALSE(fs::exists(dir / "out" / "p01.csv"));
  write_json(dir / "P05.json", web_dump(timeline, "P05", answers));
  write_json(dir / "p05.json", web_dump(timeline, "p05", answers));
  write_json(dir / "P06.json", web_dump(timeline, "P06", answers));
  const WebImportResult clash = import_web(
      spec, m, {(dir / "P05.json").string(), (dir / "p05.json").string(), (dir / "P06.json").string()}, opt);
  CHECK(clash.participants == 1);
  CHECK(clash.problems.size() == 2);
  CHECK(fs::exists(dir / "out" / "P06.csv"));
  CHECK_FALSE(fs::exists(dir / "out" / "P05.csv"));
  CHECK_FALSE(fs::exists(dir / "out" / "p05.csv"));
  // The command: a refused input writes nothing, not even the folder or its lock (finding 5); a partly
  // bad one imports the rest with exit code 0 and names the bad file.
  {
    const fs::path fresh = dir / "cli-out";
    auto cli = test::run_cli({"import-web", (dir / "results" / "_P07.json").string(), "--spec",
                              (test::source_dir() / "experiments/demo.yaml").string(), "--stimuli",
                              (dir / "stimuli").string(), "--out", fresh.string()});
    CHECK(cli.exit_code == 2);
    CHECK_FALSE(fs::exists(fresh));
  }
}

TEST_CASE("import-web carries the web consent and timing into the native files", "[study]") {
  const auto dir = test::scratch_dir("web-consent");
  const auto m = test::make_stimuli(dir / "stimuli", {{"density", {"2.22", "6.66"}}}, 1);
  ExperimentSpec spec = test::likert_spec();
  spec.protocol.consent = "Do you agree?";
  const auto qs = resolve_questions(spec.protocol);
  const auto answers = scripted_answers(m, qs);
  const nlohmann::json timeline = web_timeline(spec, m, "sha", numbered_participant_ids(2));
  auto consent_record = [&](const std::string& id, bool given) {
    return nlohmann::json{
        {"format", "crowdlab-web-data"},
        {"kind", "consent"},
        {"participant", id},
        {"order_of", id},
        {"session", 1},
        {"spec_hash", timeline["study"]["spec_hash"]},
        {"consent", {{"given", given}, {"utc", "2026-11-25T03:00:00.000Z"}, {"session", 1}}}};
  };
  // Agreed, with the page's video timing on every record (finding 6).
  nlohmann::json agreed = web_dump(timeline, "P01", answers);
  agreed["consent_record"] = consent_record("P01", true);
  for (auto& r : agreed["records"])
    r["video"] = {{"onset_utc", "2026-11-25T03:00:01.250Z"},
                  {"inter_trial_ms", 512.4},
                  {"frames_presented", 4},
                  {"frames_dropped", 1},
                  {"frame_times_ms", {0.0, 16.7, 33.3, 83.3}},
                  {"refresh_hz", 60.0},
                  {"timing_api", "requestVideoFrameCallback"}};
  write_json(dir / "P01.json", agreed);
  // Declined: no trial record, a consent record that says no (finding 3).
  nlohmann::json declined = web_dump(timeline, "P02", answers);
  declined["records"] = nlohmann::json::array();
  declined["consent_record"] = consent_record("P02", false);
  write_json(dir / "P02.json", declined);
  const WebImportOptions opt{(dir / "out").string(), (dir / "stimuli").string()};
  const WebImportResult r =
      import_web(spec, m, {(dir / "P01.json").string(), (dir / "P02.json").string()}, opt);
  CHECK(r.participants == 2);
  CHECK(r.declined == 1);
  CHECK(r.problems.empty());
  // The native session's metadata for the same decisions: the same consent object, key for key.
  ScriptedPresenter presenter(write_script(dir / "script.csv", answers, qs).string(), 0);
  SessionOptions native_opt{"P09", (dir / "stimuli").string(), (dir / "native").string(), false, "scripted",
                            true};
  const auto native = nlohmann::json::parse(slurp(run_session(spec, m, native_opt, presenter).json_path));
  const auto web_agreed = nlohmann::json::parse(slurp(dir / "out" / "P01.json"));
  const auto web_declined = nlohmann::json::parse(slurp(dir / "out" / "P02.json"));
  REQUIRE(web_agreed.contains("consent"));
  std::vector<std::string> native_keys, web_keys;
  for (const auto& [k, v] : native["consent"].items()) native_keys.push_back(k);
  for (const auto& [k, v] : web_agreed["consent"].items()) web_keys.push_back(k);
  CHECK(web_keys == native_keys);
  CHECK(web_agreed["consent"]["given"] == true);
  CHECK(web_agreed["status"] == "complete");
  CHECK(web_declined["status"] == "declined");
  CHECK(web_declined["consent"]["given"] == false);
  CHECK(web_declined["consent"]["utc"] == "2026-11-25T03:00:00.000Z");
  CHECK(read_csv((dir / "out" / "P02.csv").string()).rows.empty());
  // The timing columns, filled as natively: frames presented and dropped, the gap, the intervals
  // between the presented frames (16.7, 16.6, 50.0 ms).
  const CsvTable t = read_csv((dir / "out" / "P01.csv").string());
  REQUIRE_FALSE(t.rows.empty());
  for (size_t row = 0; row < t.rows.size(); ++row) {
    CHECK(t.cell(row, t.column("onset_utc")) == "2026-11-25T03:00:01.250Z");
    CHECK(t.cell(row, t.column("inter_trial_ms")) == "512.4");
    CHECK(t.cell(row, t.column("frames_shown")) == "4");
    CHECK(t.cell(row, t.column("frames_dropped")) == "1");
    CHECK(std::stod(t.cell(row, t.column("frame_interval_mean_ms"))) == Approx(83.3 / 3).margin(0.06));
    CHECK(t.cell(row, t.column("frame_interval_max_ms")) == "50");
  }
}

TEST_CASE("export-web writes the study folder and a JATOS archive, completion_url is validated", "[study]") {
  const auto dir = test::scratch_dir("web-export");
  const auto m = test::make_stimuli(dir / "stimuli", {{"density", {"2.22", "6.66"}}}, 1);
  ExperimentSpec spec = test::likert_spec();
  spec.protocol.completion_url = "https://app.prolific.com/submissions/complete?cc=C0DE";
  WebExportOptions opt;
  opt.stimuli_dir = (dir / "stimuli").string();
  opt.out_dir = (dir / "web").string();
  opt.jatos_path = (dir / "study.jzip").string();
  opt.participants = {"P01", "P02"};
  opt.web_source_dir = (test::source_dir() / "study_ui/web").string();
  opt.node_modules_dir = fake_node_modules(dir / "node_modules").string();
  const WebExportResult r = export_web(spec, m, opt);
  CHECK(r.clips == 3);  // v0, v1 and the practice clip
  for (const char* f : {"index.html", "crowdlab_study.js", "lib/jspsych.js", "lib/plugin-preload.js",
                        "lib/LICENSE-jspsych.txt", "clips/v0.mp4", "timeline.json"})
    CHECK(fs::is_regular_file(dir / "web" / f));
  // The page files are copies (finding 13): editing the export never edits crowdlab's source.
  for (const char* f : {"index.html", "crowdlab_study.js", "crowdlab_study.css", "lib/LICENSE-jspsych.txt"}) {
    CAPTURE(f);
    CHECK(fs::hard_link_count(dir / "web" / f) == 1);
  }
  CHECK(slurp(dir / "web" / "lib" / "LICENSE-jspsych.txt").find("Permission is hereby granted") !=
        std::string::npos);
  const auto timeline = nlohmann::json::parse(slurp((dir / "web" / "timeline.json").string()));
  CHECK(timeline["study"]["completion_url"] == spec.protocol.completion_url);
  CHECK(timeline["questions"].size() == 6);
  CHECK(timeline["questions"][0]["text"] == "Contacts made by characters between them seem natural to me");
  CHECK(timeline["orders"]["P02"].size() == 3);
  // The archive: one .jas and one folder at the top level (JATOS refuses two of either), the folder
  // holding exactly the web study's files, stored byte for byte.
  const auto entries = zip_entries(opt.jatos_path);
  REQUIRE(entries.size() == static_cast<size_t>(r.files) + 1);
  CHECK(entries[0].first == r.jatos_dir + ".jas");
  for (size_t i = 1; i < entries.size(); ++i) {
    CAPTURE(entries[i].first);
    REQUIRE(entries[i].first.rfind(r.jatos_dir + "/", 0) == 0);
    CHECK(entries[i].second == slurp(dir / "web" / entries[i].first.substr(r.jatos_dir.size() + 1)));
  }
  // The .jas: JATOS's documented schema (JATOS-Study-Archive-JZIP): "version" "3" and the required
  // fields of the study, its components and its batches.
  const auto jas = nlohmann::json::parse(entries[0].second);
  CHECK(jas["version"] == "3");
  const auto& data = jas["data"];
  const std::regex uuid("[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}");
  CHECK(std::regex_match(data["uuid"].get<std::string>(), uuid));
  CHECK(data["title"] == "crowdlab: " + spec.name);
  CHECK(data["dirName"] == r.jatos_dir);
  CHECK(data["endRedirectUrl"] == spec.protocol.completion_url);
  CHECK(data.contains("jsonData"));  // the name every JATOS 3 accepts (newer ones alias it as studyInput)
  REQUIRE(data["componentList"].size() == 1);
  const auto& component = data["componentList"][0];
  CHECK(std::regex_match(component["uuid"].get<std::string>(), uuid));
  CHECK(component["htmlFilePath"] == "index.html");
  CHECK(component["reloadable"] == true);  // a reload resumes (under JATOS, too)
  CHECK(!component["title"].get<std::string>().empty());
  REQUIRE(data["batchList"].size() == 1);
  const auto& batch = data["batchList"][0];
  CHECK(std::regex_match(batch["uuid"].get<std::string>(), uuid));
  CHECK(batch["title"] == "Default");
  CHECK(batch["allowedWorkerTypes"] ==
        nlohmann::json::array({"Jatos", "PersonalSingle", "PersonalMultiple", "GeneralMultiple"}));
  CHECK(std::set<std::string>{data["uuid"].get<std::string>(), component["uuid"].get<std::string>(),
                              batch["uuid"].get<std::string>()}
            .size() == 3);
  if (fs::exists("/usr/bin/unzip"))
    CHECK(std::system(("/usr/bin/unzip -tqq " + opt.jatos_path + " > /dev/null").c_str()) == 0);
  else
    WARN("unzip -t not run: no /usr/bin/unzip");

  // The same export again gives the same archive bytes, whatever the files' times and modes and the
  // time zone (fixed DOS time and Unix attributes, sorted entries).
  const std::string first = slurp(opt.jatos_path);
  const fs::path clip = dir / "stimuli" / "clips" / "v0.mp4";  // hard-linked into the next export
  fs::last_write_time(clip, fs::file_time_type::clock::now() - std::chrono::hours(24 * 365 * 20));
  fs::permissions(clip, fs::perms::owner_read | fs::perms::owner_write);
  const char* tz = std::getenv("TZ");
  const std::string old_tz = tz ? tz : "";
  setenv("TZ", "Pacific/Kiritimati", 1);  // UTC+14: a local-time DOS stamp would move by a day
  tzset();
  opt.out_dir = (dir / "web2").string();
  export_web(spec, m, opt);
  if (tz)
    setenv("TZ", old_tz.c_str(), 1);
  else
    unsetenv("TZ");
  tzset();
  CHECK(slurp(opt.jatos_path) == first);
  // A non-empty output folder is refused.
  CHECK_THROWS_WITH(export_web(spec, m, opt), Catch::Contains("not an empty folder"));

  // protocol.completion_url must be an http(s) URL.
  const std::string demo = slurp(test::source_dir() / "experiments/demo.yaml");
  for (const std::string url : {"ftp://x.org/", "https://", "https://a.org/x y", "javascript:alert(1)"}) {
    std::string yaml = demo;
    yaml.insert(yaml.find("  composites:"), "  completion_url: \"" + url + "\"\n");
    std::ofstream(dir / "bad.yaml") << yaml;
    CAPTURE(url);
    CHECK_THROWS_WITH(load_experiment_spec((dir / "bad.yaml").string()), Catch::Contains("completion_url"));
  }
}

TEST_CASE("the npm packages pinned for the page are exactly those export-web copies", "[study]") {
  // Every package of package.json's dependencies ships a file of the exported page, and every file comes
  // from a pinned package (issue 29: five jsPsych plugins stayed pinned after the page stopped loading them).
  std::set<std::string> shipped;
  for (const auto& [from, to] : jspsych_bundle_files()) {
    const size_t end = from.rfind('@', 0) == 0 ? from.find('/', from.find('/') + 1) : from.find('/');
    shipped.insert(from.substr(0, end));
  }
  const auto package = nlohmann::json::parse(slurp(source_dir() / "study_ui" / "web" / "package.json"));
  std::set<std::string> pinned;
  for (const auto& [name, version] : package.at("dependencies").items()) pinned.insert(name);
  CHECK(pinned == shipped);
  // The lock file holds no package the page does not load (puppeteer-core's tree aside).
  const auto lock = nlohmann::json::parse(slurp(source_dir() / "study_ui" / "web" / "package-lock.json"));
  std::set<std::string> locked;
  for (const auto& [name, entry] : lock.at("packages").items())
    if (name.find("jspsych") != std::string::npos)
      locked.insert(name.substr(std::string("node_modules/").size()));
  CHECK(locked == shipped);
  std::set<std::string> root;
  for (const auto& [name, version] : lock.at("packages").at("").at("dependencies").items()) root.insert(name);
  CHECK(root == shipped);
}

}  // namespace test_web_export
