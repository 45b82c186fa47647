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
  for (const char* f : {"index.html", "crowdlab_study.js", "lib/jspsych.js", "lib/plugin-survey-likert.js",
                        "clips/v0.mp4", "timeline.json"})
    CHECK(fs::is_regular_file(dir / "web" / f));
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

/// H.264 clips (what Chromium plays; the fixture's mp4v clips it does not) for the demo spec's eight
/// conditions: 160x90, 15 fps, 2 s, a flat colour per clip with a moving bar.
StimulusManifest h264_demo_stimuli(const fs::path& dir) {
  fs::create_directories(dir / "clips");
  StimulusManifest m;
  m.factor_names = {"density", "viewpoint", "method"};
  int variant = 0;
  for (const std::string density : {"3.33", "6.66"})
    for (const std::string view : {"V1", "V3"})
      for (const std::string method : {"baseline", "ours"}) {
        StimulusEntry e;
        e.id = "density-" + density + "_viewpoint-" + view + "_method-" + method;
        e.factors = {{"density", density}, {"viewpoint", view}, {"method", method}};
        e.file = "clips/" + e.id + ".mp4";
        stimuli::VideoEncoder encoder((dir / e.file).string(), {160, 90, 15.0, 28, "ultrafast"});
        std::vector<std::uint8_t> rgba(160 * 90 * 4);
        for (int f = 0; f < 30; ++f) {
          for (size_t p = 0; p < rgba.size(); p += 4) {
            const int x = static_cast<int>((p / 4) % 160);
            const bool bar = x >= 5 * f && x < 5 * f + 12;
            rgba[p] = static_cast<std::uint8_t>(bar ? 250 : 40 + 25 * variant);
            rgba[p + 1] = static_cast<std::uint8_t>(bar ? 250 : 90);
            rgba[p + 2] = static_cast<std::uint8_t>(bar ? 250 : 200 - 20 * variant);
            rgba[p + 3] = 255;
          }
          encoder.add_frame(rgba.data(), false);
        }
        encoder.close();
        e.duration_s = 2.0;
        e.frames = 30;
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

}  // namespace

TEST_CASE(
    "browser: a scripted participant completes the demo study in headless Chromium, resumes after a reload",
    "[study][browser]") {
  if (test::kSanitized) {
    // The browser test checks the page, not crowdlab's memory; export-web and import-web run under the
    // sanitizers in the tests above. This saves CI about 20 s.
    WARN("skipped under the sanitizers (the Release run performs it)");
    return;
  }
  const fs::path modules = test::binary_dir() / "web" / "node_modules";
  const char* chromium = "/usr/bin/chromium";
  if (!fs::exists(chromium) || !fs::is_directory(modules / "puppeteer-core") ||
      !fs::is_directory(modules / "jspsych")) {
    WARN("skipped: needs /usr/bin/chromium (scripts/install-deps.sh --test) and jsPsych + puppeteer-core in "
         << modules.string() << " (make web-deps)");
    return;
  }
  const auto dir = test::scratch_dir("web-browser");
  // The demo spec (it has instructions and a practice trial of its own), plus every other screen the
  // protocol can have: consent, two blocks in Latin-square order (the practice trial, whose method is
  // baseline, opens the 'baseline' block), a break.
  std::string yaml = slurp(test::source_dir() / "experiments" / "demo.yaml");
  REQUIRE(yaml.find("  instructions:") != std::string::npos);
  REQUIRE(yaml.find("  practice: {density: [3.33], viewpoint: [V1], method: [baseline]}") !=
          std::string::npos);
  yaml.insert(yaml.find("  scale:"),
              "  consent: \"I agree to take part in this study.\"\n"
              "  block_by: method\n  block_order: latin_square\n  break_every: 3\n");
  std::ofstream(dir / "demo-online.yaml") << yaml;
  const std::string spec_path = (dir / "demo-online.yaml").string();
  const ExperimentSpec spec = load_experiment_spec(spec_path);
  const auto m = h264_demo_stimuli(dir / "stimuli");
  const auto qs = resolve_questions(spec.protocol);
  const auto answers = scripted_answers(m, qs);
  nlohmann::json answers_json;
  for (const auto& [key, raw] : answers) answers_json[key.first][key.second] = raw;
  write_json(dir / "answers.json", answers_json);
  const std::string exe = test::crowdlab_exe().string();
  REQUIRE(run_command(exe + " export-web " + spec_path + " --stimuli " + (dir / "stimuli").string() +
                      " --out " + (dir / "web").string() + " --participants 3 --jatos " +
                      (dir / "demo.jzip").string() + " > " + (dir / "export.log").string()) == 0);

  // The participant: P02, reloading the page after 3 of the 9 trials.
  REQUIRE(run_command("node " + (test::source_dir() / "tests" / "study" / "web_participant.mjs").string() +
                      " " + (dir / "web").string() + " " + chromium + " " + modules.string() + " " +
                      (dir / "answers.json").string() + " " + (dir / "browser").string() + " P02 3") == 0);
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

  // The Likert screen fits both window sizes without scrolling, the clip as large as the statements
  // leave (at least half the window's height here), the six statements in three columns of two rows.
  const auto layout = nlohmann::json::parse(slurp(dir / "browser" / "layout.json"));
  for (const std::string size : {"1920x1080", "1440x900"}) {
    CAPTURE(size, layout[size].dump());
    const auto& l = layout[size];
    const double width = l["viewport"][0], height = l["viewport"][1];
    CHECK(l["scroll"][0].get<double>() <= width);
    CHECK(l["scroll"][1].get<double>() <= height);
    CHECK(l["next_bottom"].get<double>() <= height);
    CHECK(l["picture"][1].get<double>() >= 0.5 * height);
    std::set<int> lefts, tops;
    for (const auto& st : l["statements"]) {
      lefts.insert(static_cast<int>(st[0].get<double>()));
      tops.insert(static_cast<int>(st[1].get<double>()));
    }
    CHECK(lefts.size() == 3);
    CHECK(tops.size() == 2);
    for (size_t q = 0; q < 6; ++q)  // each scale lies under its statement, as wide as its column
      CHECK(l["scales"][q][0].get<double>() <= l["statements"][q][0].get<double>() + 1);
  }

  // import-web of the download equals the native scripted session with the same answers.
  REQUIRE(run_command(exe + " import-web " + (dir / "browser" / "download.json").string() + " --spec " +
                      spec_path + " --stimuli " + (dir / "stimuli").string() + " --out " +
                      (dir / "web-responses").string() + " > " + (dir / "import.log").string()) == 0);
  const auto script = write_script(dir / "script.csv", answers, qs);
  REQUIRE(run_command(exe + " study " + spec_path + " --participant P02 --stimuli " +
                      (dir / "stimuli").string() + " --responses " + script.string() + " --out " +
                      (dir / "native").string() + " > " + (dir / "native.log").string()) == 0);
  const std::vector<std::string> differ = {"session", "rt_ms",
                                           "timestamp"};  // reload; real vs scripted times
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
