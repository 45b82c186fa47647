// The web study in headless Chromium (skipped, with a message, when chromium or jsPsych are absent): the
// page shows the same screens, headers and texts as the native session (parity), records a declined
// consent, and a scripted participant completes and resumes the demo study. The export and import
// without a browser are test_web_export.cpp.
#include <sys/wait.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "framework/core/csv.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "stimuli/video_encoder.hpp"
#include "study_ui/run_session.hpp"
#include "study_ui/scripted_presenter.hpp"
#include "study_ui/trial_screen.hpp"
#include "study_ui/web_export.hpp"
#include "tests/study/web_fixture.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_web_browser {

using namespace crowdlab;
using namespace crowdlab::study;
namespace fs = std::filesystem;
using crowdlab::test::slurp;
using namespace crowdlab::test::web;

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
    if (e.contains("screen") && e["screen"] == "finished") e.erase("hint");
  return t;
}

/// A stand-in for the jatos.js that JATOS serves beside a component's HTML file (JATOS >= 3.3.1: the
/// page's `<script src="jatos.js">`), written into the exported folder: the calls the page makes, as
/// jatos.js documents them (onLoad calls back once initialised; appendResultData(data) returns a
/// Promise; endStudy(); endStudyAjax(successful, message) (ends without JATOS's end redirect, returns a
/// Promise); endStudyAndRedirect(url); urlQueryParameters: the study link's query; workerId).
/// Every call is logged in window.jatosStub with the number of appends still unanswered at that moment;
/// each append answers after `append_ms`, so a page that ended the study without waiting for its last
/// append would be caught with one still open.
void write_jatos_stub(const fs::path& web_dir, int worker_id, const nlohmann::json& query, int append_ms) {
  std::ofstream(web_dir / "jatos.js")
      << "// Stub of JATOS's jatos.js for crowdlab's browser test (tests/study/test_web_browser.cpp).\n"
      << "window.jatosStub = { log: [], lines: [], open: 0, ended: null };\n"
      << "window.jatos = {\n"
      << "  workerId: " << worker_id << ",\n"
      << "  urlQueryParameters: " << query.dump() << ",\n"
      << "  onLoad(callback) {\n"
      << "    jatosStub.log.push({ call: 'onLoad' });\n"
      << "    setTimeout(() => { jatosStub.log.push({ call: 'initialised' }); callback(); }, 100);\n"
      << "  },\n"
      << "  appendResultData(data) {\n"
      << "    const n = jatosStub.log.filter((e) => e.call === 'appendResultData').length;\n"
      << "    jatosStub.log.push({ call: 'appendResultData', n, open: jatosStub.open, type: typeof data });\n"
      << "    jatosStub.open++;\n"
      << "    return new Promise((resolve) => setTimeout(() => {\n"
      << "      jatosStub.lines.push(data);\n"
      << "      jatosStub.open--;\n"
      << "      jatosStub.log.push({ call: 'appended', n });\n"
      << "      resolve();\n"
      << "    }, " << append_ms << "));\n"
      << "  },\n"
      << "  endStudy(...args) {\n"
      << "    jatosStub.log.push({ call: 'endStudy', args, open: jatosStub.open });\n"
      << "    jatosStub.ended = 'endStudy';\n"
      << "  },\n"
      << "  endStudyAjax(...args) {\n"
      << "    jatosStub.log.push({ call: 'endStudyAjax', args, open: jatosStub.open });\n"
      << "    jatosStub.ended = 'endStudyAjax';\n"
      << "    return Promise.resolve();\n"
      << "  },\n"
      << "  endStudyAndRedirect(url, ...rest) {\n"
      << "    jatosStub.log.push({ call: 'endStudyAndRedirect', url, rest, open: jatosStub.open });\n"
      << "    jatosStub.ended = 'endStudyAndRedirect';\n"
      << "  },\n"
      << "};\n";
}

/// What the stub saw, checked against what JATOS needs: jatos.js was fetched beside index.html (under
/// the study's path), the study started only from onLoad's callback, appends went one at a time, and
/// the one end call `end` came last, after every append had been answered. Returns the appended lines.
std::vector<nlohmann::json> check_jatos_run(const fs::path& out, const std::string& prefix,
                                            const std::string& end) {
  const auto requests = nlohmann::json::parse(slurp(out / "requests.json"));
  CHECK(std::find(requests.begin(), requests.end(), prefix + "jatos.js") != requests.end());
  const auto stub = nlohmann::json::parse(slurp(out / "jatos.json"));
  INFO("jatos stub: " << stub.dump(1));
  const auto& log = stub["log"];
  REQUIRE(log.size() >= 3);
  CHECK(log[0]["call"] == "onLoad");
  CHECK(log[1]["call"] == "initialised");
  int appends = 0, answered = 0, ends = 0;
  for (const auto& e : log) {
    if (e["call"] == "appendResultData") {
      CHECK(e["n"] == appends++);
      CHECK(e["open"] == 0);  // the previous append had been answered: in order, one at a time
      CHECK(e["type"] == "string");
    } else if (e["call"] == "appended") {
      CHECK(e["n"] == answered++);
    } else if (e["call"] == "endStudy" || e["call"] == "endStudyAndRedirect" || e["call"] == "endStudyAjax") {
      ++ends;
      CHECK(e["call"] == end);
      CHECK(e["open"] == 0);  // nothing still being sent
      CHECK(answered == appends);
    }
  }
  CHECK(ends == 1);
  CHECK(log.back()["call"] == end);
  CHECK(stub["ended"] == end);
  std::vector<nlohmann::json> lines;
  for (const auto& line : stub["lines"]) {
    const std::string text = line.get<std::string>();
    CHECK(text.back() == '\n');  // one JSON line per append
    CHECK(std::count(text.begin(), text.end(), '\n') == 1);
    lines.push_back(nlohmann::json::parse(text));
  }
  CHECK(lines.size() == static_cast<size_t>(appends));
  // The result data as JATOS exports them: the appended lines one after another.
  std::ofstream results(out / "jatos-results.txt");
  for (const auto& line : stub["lines"]) results << line.get<std::string>();
  return lines;
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
  std::string yaml = demo_online_yaml();
  yaml.insert(yaml.find("  scale:"), "  completion_url: \"https://panel.example/done?cc=C0DE\"\n");
  const WebStudy w = export_study(
      test::scratch_dir("web-decline"), yaml,
      {{"density", {"3.33", "6.66"}}, {"viewpoint", {"V1", "V3"}}, {"method", {"baseline", "ours"}}});
  run_participant(w, modules, "browser", {{"decline", true}});
  // No completion link for a decline (it would submit the study as completed on a panel): the page asks
  // to return the study instead.
  const std::string end_text = slurp(w.dir / "browser" / "end.json");
  CHECK(end_text.find("Finish and return to the panel") == std::string::npos);
  CHECK(end_text.find("return the study") != std::string::npos);
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
  for (const auto& e : transcript[1]) CHECK_FALSE((e.contains("screen") && e.at("screen") == "consent"));
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
  // The native window's background, read from a screen it draws (BGR), as CSS writes it.
  cv::Mat native_screen(720, 1280, CV_8UC3);
  draw_inter_trial(native_screen, layout_trial_screen({1280, 720}, qs), true);
  const cv::Vec3b bg = native_screen.at<cv::Vec3b>(1, 1);
  const std::string native_background =
      "rgb(" + std::to_string(bg[2]) + ", " + std::to_string(bg[1]) + ", " + std::to_string(bg[0]) + ")";
  CHECK(native_background == "rgb(230, 233, 236)");
  for (const std::string size : {"1280x720", "1366x768", "1440x900", "1920x1080"}) {
    CAPTURE(size, layout[size].dump());
    const auto& l = layout[size];
    const double width = l["viewport"][0], height = l["viewport"][1];
    CHECK(l["scroll"][0].get<double>() <= width);
    CHECK(l["scroll"][1].get<double>() <= height);
    CHECK(l["next_bottom"].get<double>() <= height);
    CHECK(l["picture"][1].get<double>() >= 0.5 * height);
    CHECK(l["background"] == native_background);
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

TEST_CASE(
    "browser: under JATOS the id comes from JATOS, every record and the consent are appended in order, the "
    "study ends after the last append, and the appended lines import as the download does",
    "[study][browser]") {
  const fs::path modules = browser_modules();
  if (modules.empty()) return;
  const std::vector<std::pair<std::string, std::vector<std::string>>> factors = {
      {"density", {"3.33", "6.66"}}, {"viewpoint", {"V1", "V3"}}, {"method", {"baseline", "ours"}}};
  const std::string exe = test::crowdlab_exe().string();
  const std::string prefix = "/publix/3f9c2a/";  // JATOS serves a study's files under its own path
  auto import = [&](const WebStudy& w, const std::string& in, const std::string& out) {
    return run_command(exe + " import-web " + in + " --spec " + w.spec_path + " --stimuli " +
                       (w.dir / "stimuli").string() + " --out " + (w.dir / out).string() + " > " +
                       (w.dir / (out + ".log")).string() + " 2>&1");
  };
  SECTION("a participant from a general link (worker id) completes; the end goes to the completion link") {
    std::string yaml = demo_online_yaml();
    yaml.insert(yaml.find("  scale:"), "  completion_url: \"https://panel.example/done?cc=C0DE\"\n");
    const WebStudy w = export_study(test::scratch_dir("web-jatos"), yaml, factors);
    write_jatos_stub(w.dir / "web", 17, nlohmann::json::object(), 250);
    // No id in the page's own link: JATOS keeps the study link's query in jatos.urlQueryParameters.
    run_participant(w, modules, "browser", {{"jatos", true}, {"participant", ""}, {"path_prefix", prefix}});
    const fs::path out = w.dir / "browser";
    const auto lines = check_jatos_run(out, prefix, "endStudyAndRedirect");
    const auto stub = nlohmann::json::parse(slurp(out / "jatos.json"));
    CHECK(stub["log"].back()["url"] == "https://panel.example/done?cc=C0DE");
    // The id is JATOS's worker id; the page never asked for one (the participant fails on an id field).
    const auto stored = nlohmann::json::parse(slurp(out / "localstorage.json"));
    CHECK(stored["participant"] == "jatos17");
    CHECK(stored["complete"] == true);
    CHECK(stored["sessions"][0]["jatos"] == true);
    // The consent first, then each trial's record once, in order, exactly as stored.
    REQUIRE(lines.size() == 1 + stored["records"].size());
    CHECK(lines[0] == stored["consent_record"]);
    CHECK(lines[0]["consent"]["given"] == true);
    for (size_t i = 1; i < lines.size(); ++i) {
      CHECK(lines[i] == stored["records"][i - 1]);
      CHECK(lines[i]["trial"] == static_cast<int>(i));
    }
    CHECK(stored["records"].size() == w.manifest.entries.size());
    // The end screen of the plan, then the page waits; no download under JATOS.
    CHECK(slurp(out / "end.json").find("Saving your answers") != std::string::npos);
    // Its short body where every text screen's body starts (15 % of the width, as natively), not
    // shrunk to its text and centred.
    CHECK(nlohmann::json::parse(slurp(out / "end-layout.json"))["body_left"].get<double>() ==
          Approx(0.15).margin(0.005));
    CHECK_FALSE(fs::exists(out / "download.json"));
    // The appended lines, saved as JATOS exports them, import to the same files as the participant's data
    // file (the download is the stored data, byte for byte: the stand-alone test checks that).
    std::ofstream(out / "download.json") << stored.dump(1);
    REQUIRE(import(w, (out / "jatos-results.txt").string(), "from-jatos") == 0);
    REQUIRE(import(w, (out / "download.json").string(), "from-download") == 0);
    CHECK(read_csv((w.dir / "from-jatos" / "jatos17.csv").string()).rows.size() ==
          w.manifest.entries.size() * resolve_questions(w.spec.protocol).size());
    CHECK(slurp(w.dir / "from-jatos" / "jatos17.csv") == slurp(w.dir / "from-download" / "jatos17.csv"));
    const auto meta = nlohmann::json::parse(slurp(w.dir / "from-jatos" / "jatos17.json"));
    CHECK(meta["consent"] == stored["consent_record"]["consent"]);
    CHECK(meta["status"] == "complete");
  }
  SECTION(
      "a participant from a panel link (query id) declines; the consent is appended, then the study ends as "
      "unsuccessful without going to the completion link") {
    std::string yaml = demo_online_yaml();
    yaml.insert(yaml.find("  scale:"), "  completion_url: \"https://panel.example/done?cc=C0DE\"\n");
    const WebStudy w = export_study(test::scratch_dir("web-jatos-decline"), yaml, factors);
    write_jatos_stub(w.dir / "web", 18, {{"participant", "P05"}}, 250);
    run_participant(w, modules, "browser",
                    {{"jatos", true}, {"participant", ""}, {"path_prefix", prefix}, {"decline", true}});
    const fs::path out = w.dir / "browser";
    const auto lines = check_jatos_run(out, prefix, "endStudyAjax");
    // A decline is not a completion: on a panel the completion link would submit (and pay) the study.
    const auto stub = nlohmann::json::parse(slurp(out / "jatos.json"));
    CHECK(stub["log"].back()["args"] == nlohmann::json::array({false, "consent declined"}));
    CHECK(slurp(out / "end.json").find("return the study") != std::string::npos);
    REQUIRE(lines.size() == 1);
    CHECK(lines[0]["kind"] == "consent");
    CHECK(lines[0]["participant"] == "P05");  // the query's id wins over the worker id
    CHECK(lines[0]["consent"]["given"] == false);
    REQUIRE(import(w, (out / "jatos-results.txt").string(), "from-jatos") == 0);
    const auto meta = nlohmann::json::parse(slurp(w.dir / "from-jatos" / "P05.json"));
    CHECK(meta["status"] == "declined");
    CHECK(meta["consent"] == lines[0]["consent"]);
  }
}

}  // namespace test_web_browser
