// The web study (export-web / import-web): trial orders equal to the native session's, the import of
// web records into native tidy CSVs, refusal of bad input, the JATOS archive's structure, and a real
// participant in headless Chromium (skipped, with a message, when chromium or jsPsych are absent).
#include <sys/wait.h>

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

namespace {

/// H.264 clips (what Chromium plays; the fixture's mp4v clips it does not), one per crossing of
/// `factors`, plus one practice clip (the first clip again, with `practice_levels`): 160x90, 15 fps,
/// 10 frames (0.67 s, so the minimum viewing time stays short), a flat colour per clip with a moving bar.
StimulusManifest h264_stimuli(const fs::path& dir,
                              const std::vector<std::pair<std::string, std::vector<std::string>>>& factors) {
  fs::create_directories(dir / "clips");
  StimulusManifest m;
  std::vector<std::map<std::string, std::string>> cells = {{}};
  for (const auto& [name, levels] : factors) {
    m.factor_names.push_back(name);
    std::vector<std::map<std::string, std::string>> next;
    for (const auto& cell : cells)
      for (const auto& level : levels) {
        auto c = cell;
        c[name] = level;
        next.push_back(c);
      }
    cells = next;
  }
  int variant = 0;
  for (const auto& cell : cells) {
    StimulusEntry e;
    for (const auto& [name, levels] : factors) e.id += (e.id.empty() ? "" : "_") + name + "-" + cell.at(name);
    e.factors = cell;
    e.file = "clips/" + e.id + ".mp4";
    stimuli::VideoEncoder encoder((dir / e.file).string(), {160, 90, 15.0, 28, "ultrafast"});
    std::vector<std::uint8_t> rgba(160 * 90 * 4);
    for (int f = 0; f < 10; ++f) {
      for (size_t p = 0; p < rgba.size(); p += 4) {
        const int x = static_cast<int>((p / 4) % 160);
        const bool bar = x >= 14 * f && x < 14 * f + 12;
        rgba[p] = static_cast<std::uint8_t>(bar ? 250 : 40 + 17 * variant);
        rgba[p + 1] = static_cast<std::uint8_t>(bar ? 250 : 90);
        rgba[p + 2] = static_cast<std::uint8_t>(bar ? 250 : 200 - 13 * variant);
        rgba[p + 3] = 255;
      }
      encoder.add_frame(rgba.data(), false);
    }
    encoder.close();
    e.duration_s = 10.0 / 15.0;
    e.frames = 10;
    e.width = 160;
    e.height = 90;
    e.sha256 = sha256_file_hex((dir / e.file).string());
    m.entries.push_back(e);
    ++variant;
  }
  StimulusEntry practice = m.entries.front();  // the first clip again, as the practice example
  practice.id = "practice_1";
  practice.practice = true;
  m.entries.push_back(practice);
  write_manifest(m, (dir / "manifest.csv").string());
  return m;
}

int run_command(const std::string& command) {
  INFO(command);
  const int rc = std::system(command.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/// Where the browser tests run: chromium, jsPsych and puppeteer-core; empty (with a message) when any
/// is missing, or under the sanitizers (the page is tested, not crowdlab's memory; export-web and
/// import-web run under the sanitizers in the tests above).
fs::path browser_modules() {
  if (test::kSanitized) {
    WARN("skipped under the sanitizers (the Release run performs it)");
    return {};
  }
  const fs::path modules = test::binary_dir() / "web" / "node_modules";
  if (!fs::exists("/usr/bin/chromium") || !fs::is_directory(modules / "puppeteer-core") ||
      !fs::is_directory(modules / "jspsych")) {
    WARN("skipped: needs /usr/bin/chromium (scripts/install-deps.sh --test) and jsPsych + puppeteer-core in "
         << modules.string() << " (make web-deps)");
    return {};
  }
  return modules;
}

/// The demo spec plus every other screen the protocol can have: consent, two blocks in Latin-square
/// order (the practice trial, whose method is baseline, opens the 'baseline' block), a break.
std::string demo_online_yaml() {
  std::string yaml = slurp(test::source_dir() / "experiments" / "demo.yaml");
  REQUIRE(yaml.find("  instructions:") != std::string::npos);
  REQUIRE(yaml.find("  practice: {density: [3.33], viewpoint: [V1], method: [baseline]}") !=
          std::string::npos);
  yaml.insert(yaml.find("  scale:"),
              "  consent: \"I agree to take part in this study.\"\n"
              "  block_by: method\n  block_order: latin_square\n  break_every: 3\n");
  return yaml;
}

/// A 2AFC copy of hoyet2016_pairs.yaml: shoulder 0/2 x distance 0.20/0.45/0.70, one repetition, one
/// practice pair.
std::string afc_pairs_yaml() {
  std::string yaml = slurp(test::source_dir() / "experiments" / "hoyet2016_pairs.yaml");
  auto replace_line = [&](const std::string& starts, const std::string& with) {
    const size_t at = yaml.find(starts);
    REQUIRE(at != std::string::npos);
    yaml.replace(at, yaml.find('\n', at) - at, with);
  };
  replace_line("  shoulder: [0, 1, 2]", "  shoulder: [0, 2]");
  replace_line("  distance: [0.20, 0.25", "  distance: [0.20, 0.45, 0.70]");
  replace_line("repetitions:", "repetitions: 1");
  replace_line("    shoulder: [0, 1, 2]", "    shoulder: [0]");
  replace_line("    distance: [0.20, 0.70]", "    distance: [0.20]");
  return yaml;
}

/// One web study in a scratch folder: the spec, H.264 stimuli, the answers, the export.
struct WebStudy {
  fs::path dir;
  std::string spec_path;
  ExperimentSpec spec;
  StimulusManifest manifest;
  std::map<std::pair<std::string, std::string>, int> answers;
};

WebStudy export_study(const fs::path& dir, const std::string& yaml,
                      const std::vector<std::pair<std::string, std::vector<std::string>>>& factors) {
  WebStudy w;
  w.dir = dir;
  std::ofstream(dir / "spec.yaml") << yaml;
  w.spec_path = (dir / "spec.yaml").string();
  w.spec = load_experiment_spec(w.spec_path);
  w.manifest = h264_stimuli(dir / "stimuli", factors);
  w.answers = scripted_answers(w.manifest, resolve_questions(w.spec.protocol));
  nlohmann::json answers_json;
  for (const auto& [key, raw] : w.answers) answers_json[key.first][key.second] = raw;
  write_json(dir / "answers.json", answers_json);
  REQUIRE(run_command(test::crowdlab_exe().string() + " export-web " + w.spec_path + " --stimuli " +
                      (dir / "stimuli").string() + " --out " + (dir / "web").string() +
                      " --participants 3 > " + (dir / "export.log").string()) == 0);
  return w;
}

/// The scripted participant (web_participant.mjs) on the exported page; `extra` adds options.
void run_participant(const WebStudy& w, const fs::path& modules, const std::string& out,
                     nlohmann::json extra) {
  extra["web_dir"] = (w.dir / "web").string();
  extra["chromium"] = "/usr/bin/chromium";
  extra["node_modules"] = modules.string();
  extra["answers"] = (w.dir / "answers.json").string();
  extra["out_dir"] = (w.dir / out).string();
  if (!extra.contains("participant")) extra["participant"] = "P02";
  write_json(w.dir / (out + "-options.json"), extra);
  REQUIRE(run_command("node " + (test::source_dir() / "tests" / "study" / "web_participant.mjs").string() +
                      " " + (w.dir / (out + "-options.json")).string() + " > " +
                      (w.dir / (out + ".log")).string() + " 2>&1") == 0);
}

/// A transcript without the end screen's hint line: the native window says which key closes it, the
/// page what to do with the data instead (docs/online.md lists this difference).
nlohmann::json comparable_transcript(nlohmann::json t) {
  for (auto& e : t)
    if (e.value("screen", "") == "finished") e.erase("hint");
  return t;
}

}  // namespace

TEST_CASE(
    "browser: lab and online show the same screens, headers and texts (demo, 2AFC pairs, consent + "
    "breaks + two blocks)",
    "[study][browser]") {
  const fs::path modules = browser_modules();
  if (modules.empty()) return;
  const auto root = test::scratch_dir("web-parity");
  const std::vector<std::pair<std::string, std::vector<std::string>>> demo_factors = {
      {"density", {"3.33", "6.66"}}, {"viewpoint", {"V1", "V3"}}, {"method", {"baseline", "ours"}}};
  struct Case {
    std::string name, yaml;
    std::vector<std::pair<std::string, std::vector<std::string>>> factors;
  };
  const std::vector<Case> cases = {
      {"demo", slurp(test::source_dir() / "experiments" / "demo.yaml"), demo_factors},
      {"afc-pairs",
       afc_pairs_yaml(),
       {{"shoulder", {"0", "2"}}, {"distance", {"0.20", "0.45", "0.70"}}, {"viewpoint", {"pair"}}}},
      {"demo-online", demo_online_yaml(), demo_factors}};
  for (const Case& c : cases) {
    CAPTURE(c.name);
    fs::create_directories(root / c.name);
    const WebStudy w = export_study(root / c.name, c.yaml, c.factors);
    run_participant(w, modules, "browser", {});
    const auto web = nlohmann::json::parse(slurp(w.dir / "browser" / "transcript.json"));
    REQUIRE(web.size() == 1);  // one page load
    // The native session of the same id, as the scripted presenter is asked to show it.
    const auto qs = resolve_questions(w.spec.protocol);
    ScriptedPresenter native(write_script(w.dir / "script.csv", w.answers, qs).string(), 0);
    SessionOptions opt{"P02", (w.dir / "stimuli").string(), (w.dir / "native").string(), false, "scripted",
                       true};
    REQUIRE(run_session(w.spec, w.manifest, opt, native).complete);
    INFO("native: " << native.transcript().dump(1) << "\nweb: " << web[0].dump(1));
    CHECK(comparable_transcript(web[0]) == comparable_transcript(native.transcript()));
    size_t trials = 0;
    for (const auto& e : web[0]) trials += e.contains("trial");
    CHECK(trials == w.manifest.entries.size());
  }
}

TEST_CASE("browser: a declined consent is recorded online and imported as natively", "[study][browser]") {
  const fs::path modules = browser_modules();
  if (modules.empty()) return;
  const WebStudy w = export_study(
      test::scratch_dir("web-decline"), demo_online_yaml(),
      {{"density", {"3.33", "6.66"}}, {"viewpoint", {"V1", "V3"}}, {"method", {"baseline", "ours"}}});
  run_participant(w, modules, "browser", {{"decline", true}});
  const auto download = nlohmann::json::parse(slurp(w.dir / "browser" / "download.json"));
  CHECK(download["records"].empty());
  REQUIRE(download.contains("consent_record"));
  CHECK(download["consent_record"]["consent"]["given"] == false);
  CHECK(download["consent_record"]["consent"]["session"] == 1);
  REQUIRE(run_command(test::crowdlab_exe().string() + " import-web " +
                      (w.dir / "browser" / "download.json").string() + " --spec " + w.spec_path +
                      " --stimuli " + (w.dir / "stimuli").string() + " --out " +
                      (w.dir / "imported").string() + " > " + (w.dir / "import.log").string()) == 0);
  const auto meta = nlohmann::json::parse(slurp(w.dir / "imported" / "P02.json"));
  CHECK(meta["status"] == "declined");
  CHECK(meta["consent"] == download["consent_record"]["consent"]);
  CHECK(read_csv((w.dir / "imported" / "P02.csv").string()).rows.empty());
}

TEST_CASE(
    "browser: a scripted participant completes the demo study in headless Chromium, resumes after a reload",
    "[study][browser]") {
  const fs::path modules = browser_modules();
  if (modules.empty()) return;
  const auto dir = test::scratch_dir("web-browser");
  // A minimum viewing time well above the time the early keys take, so that they surely fall in it.
  std::string yaml = demo_online_yaml();
  yaml.insert(yaml.find("  scale:"), "  min_view_ms: 1500\n");
  const WebStudy w = export_study(
      dir, yaml,
      {{"density", {"3.33", "6.66"}}, {"viewpoint", {"V1", "V3"}}, {"method", {"baseline", "ours"}}});
  const std::string spec_path = w.spec_path;
  const auto& m = w.manifest;
  const auto qs = resolve_questions(w.spec.protocol);
  const auto& answers = w.answers;
  const std::string exe = test::crowdlab_exe().string();
  // The participant: P02, reloading the page after 3 of the 9 trials, trying to answer too early, with
  // the first trial screen measured at four window sizes; before that, the ids the page must refuse.
  run_participant(w, modules, "browser",
                  {{"reload_after", 3},
                   {"early_input", true},
                   {"id_checks", true},
                   {"layout_sizes", {{1280, 720}, {1366, 768}, {1440, 900}, {1920, 1080}}}});
  const auto resume = nlohmann::json::parse(slurp(dir / "browser" / "resume.json"));
  CHECK(resume["before"].size() == 3);
  CHECK(resume["first_trial_after_reload"] == 4);  // the first unanswered trial
  CHECK(resume["answered"].size() == 9);           // every trial answered once (8 + practice)
  const auto download = nlohmann::json::parse(slurp(dir / "browser" / "download.json"));
  CHECK(download == nlohmann::json::parse(slurp(dir / "browser" / "localstorage.json")));
  CHECK(download["complete"] == true);
  CHECK(download["sessions"].size() == 2);
  REQUIRE(download["records"].size() == 9);
  for (const auto& r : download["records"]) {
    CAPTURE(r["trial"]);
    CHECK(r["session"] == (r["trial"].get<int>() <= 3 ? 1 : 2));
    CHECK(r["video"]["timing_api"] == "requestVideoFrameCallback");
    CHECK(r["video"]["frames_presented"].get<int>() > 0);  // the clip really played
    CHECK(r["video"]["refresh_hz"].get<double>() > 0);
    CHECK(r["answers"][0]["rt_ms"].get<double>() > 0);
  }
  // The page's FNV-1a equals crowdlab's (the rule for ids that are not embedded).
  for (const auto& [text, hash] : nlohmann::json::parse(slurp(dir / "browser" / "fnv.json"))
                                      .get<std::vector<std::pair<std::string, std::uint32_t>>>())
    CHECK(hash == fnv1a32(text));

  // The end page says what to do with the download (finding 14).
  CHECK(slurp(dir / "browser" / "end.json").find("send it to the experimenter") != std::string::npos);
  // After the reload the page resumed by the plan's rule: the instructions again, no consent.
  const auto transcript = nlohmann::json::parse(slurp(dir / "browser" / "transcript.json"));
  REQUIRE(transcript.size() == 2);
  CHECK(transcript[1][0]["screen"] == "instructions");
  for (const auto& e : transcript[1]) CHECK(e.value("screen", "") != "consent");
  // Ids (findings 1, 2): what import-web refuses never starts; a bare link shows an empty field that
  // refuses a bad id with the rule, and stores nothing.
  const auto ids = nlohmann::json::parse(slurp(dir / "browser" / "ids.json"));
  for (const std::string bad : {"_P07", "-P07", "P 07"}) {
    CAPTURE(bad, ids[bad].dump());
    CHECK(ids[bad]["refused"] == true);
    CHECK(ids[bad]["text"].get<std::string>().find("starting with a letter or digit") != std::string::npos);
  }
  CHECK(ids["bare"]["value"] == "");
  CHECK(ids["bare"]["error"].get<std::string>().find("starting with a letter or digit") != std::string::npos);
  CHECK(ids["bare"]["url_after_bad"].get<std::string>().find("participant=") == std::string::npos);
  CHECK(ids["bare"]["storage_keys"] == 0);
  // Minimum viewing time (finding 11): keys typed on the inter-trial screen and keys and a click right
  // after the onset answered nothing; the screen said the answers were locked.
  const auto early = nlohmann::json::parse(slurp(dir / "browser" / "early.json"));
  INFO(early.dump());
  CHECK(early["after_onset"]["locked"] == true);
  CHECK(early["after_onset"]["selected"] == 0);
  CHECK(early["after_onset"]["still_here"] == true);
  CHECK(early["after_onset"]["next_label"] == "Watch the clip");
  CHECK(early["during_inter_trial"]["was_inter_trial"] == true);
  CHECK(early["during_inter_trial"]["selected"] == 0);
  for (const auto& r : download["records"])
    for (const auto& a : r["answers"]) {
      CAPTURE(r["trial"]);
      CHECK(a["rt_ms"].get<double>() >= 1500.0);  // min_view_ms
    }
  // Consent online (finding 3): recorded with the decision, its UTC time and session.
  REQUIRE(download.contains("consent_record"));
  CHECK(download["consent_record"]["consent"]["given"] == true);
  CHECK(download["consent_record"]["consent"]["session"] == 1);

  // Layout (findings 9, 10): at 1280x720, 1366x768, 1440x900 and 1920x1080 the trial screen does not
  // scroll, the clip is at least half the window high, the native background, and the six statements
  // in three columns of two rows, filled column by column as natively (Q1/Q2 share a column).
  const auto layout = nlohmann::json::parse(slurp(dir / "browser" / "layout.json"));
  for (const std::string size : {"1280x720", "1366x768", "1440x900", "1920x1080"}) {
    CAPTURE(size, layout[size].dump());
    const auto& l = layout[size];
    const double width = l["viewport"][0], height = l["viewport"][1];
    CHECK(l["scroll"][0].get<double>() <= width);
    CHECK(l["scroll"][1].get<double>() <= height);
    CHECK(l["next_bottom"].get<double>() <= height);
    CHECK(l["picture"][1].get<double>() >= 0.5 * height);
    CHECK(l["background"] == "rgb(230, 233, 236)");
    std::set<int> lefts, tops;
    for (const auto& c : l["cells"]) {
      lefts.insert(static_cast<int>(c[0].get<double>()));
      tops.insert(static_cast<int>(c[1].get<double>()));
    }
    CHECK(lefts.size() == 3);
    CHECK(tops.size() == 2);
    CHECK(l["cells"][0][0] == l["cells"][1][0]);  // Q1 above Q2
    CHECK(l["cells"][1][1].get<double>() > l["cells"][0][1].get<double>());
  }

  // import-web of the download equals the native scripted session with the same answers.
  REQUIRE(run_command(exe + " import-web " + (dir / "browser" / "download.json").string() + " --spec " +
                      spec_path + " --stimuli " + (dir / "stimuli").string() + " --out " +
                      (dir / "web-responses").string() + " > " + (dir / "import.log").string()) == 0);
  const auto script = write_script(dir / "script.csv", answers, qs);
  REQUIRE(run_command(exe + " study " + spec_path + " --participant P02 --stimuli " +
                      (dir / "stimuli").string() + " --responses " + script.string() + " --out " +
                      (dir / "native").string() + " > " + (dir / "native.log").string()) == 0);
  // Differ: the reload (session); real vs scripted times; the page's measured playback (finding 6: the
  // native scripted session measures none, the web import carries the page's).
  const std::vector<std::string> differ = {"session",
                                           "rt_ms",
                                           "timestamp",
                                           "onset_utc",
                                           "inter_trial_ms",
                                           "frames_shown",
                                           "frames_dropped",
                                           "frame_interval_mean_ms",
                                           "frame_interval_p99_ms",
                                           "frame_interval_max_ms"};
  {
    const CsvTable t = read_csv((dir / "web-responses" / "P02.csv").string());
    for (size_t r = 0; r < t.rows.size(); ++r) {
      CHECK(t.cell(r, t.column("onset_utc")).size() == 24);
      CHECK(std::stod(t.cell(r, t.column("inter_trial_ms"))) >= 450.0);
      CHECK(std::stol(t.cell(r, t.column("frames_shown"))) > 0);
      CHECK_FALSE(t.cell(r, t.column("frame_interval_mean_ms")).empty());
    }
  }
  CHECK(comparable_rows((dir / "web-responses" / "P02.csv").string(), differ) ==
        comparable_rows((dir / "native" / "P02.csv").string(), differ));
  // jsPsych's own CSV data of the two page loads (trials 1-3, then 4-9) imports to the same table.
  REQUIRE(run_command(exe + " import-web " + (dir / "browser" / "jspsych-1.csv").string() + " " +
                      (dir / "browser" / "jspsych-2.csv").string() + " --spec " + spec_path + " --stimuli " +
                      (dir / "stimuli").string() + " --out " + (dir / "csv-responses").string() + " > " +
                      (dir / "import-csv.log").string()) == 0);
  CHECK(slurp(dir / "csv-responses" / "P02.csv") == slurp(dir / "web-responses" / "P02.csv"));
  // analyze report reads the imported folder unchanged, here beside lab sessions of three other ids who
  // answered differently (an RM-ANOVA needs three participants, and error variance in every effect).
  for (const int lab : {1, 3, 4}) {
    const std::string id = "P0" + std::to_string(lab);
    const auto lab_script = write_script(dir / (id + "-script.csv"), scripted_answers(m, qs, lab), qs);
    REQUIRE(run_command(exe + " study " + spec_path + " --participant " + id + " --stimuli " +
                        (dir / "stimuli").string() + " --responses " + lab_script.string() + " --out " +
                        (dir / "web-responses").string() + " > " + (dir / "native.log").string()) == 0);
  }
  CHECK(run_command(exe + " analyze report " + (dir / "web-responses").string() + " --spec " + spec_path +
                    " --out " + (dir / "report").string() + " > " + (dir / "report.log").string() +
                    " 2>&1") == 0);
}
