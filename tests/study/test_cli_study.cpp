// The real `crowdlab study` / `simulate-study` / `power` binaries, as a user's shell would run them:
// scripted sessions, used-id refusal, SIGKILL of a running session and --resume, and the Xvfb +
// xdotool participant test of the native window (skipped with a warning without Xvfb/xdotool).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include <opencv2/imgcodecs.hpp>

#include "framework/core/csv.hpp"
#include "study_ui/study_question.hpp"
#include "study_ui/trial_screen.hpp"
#include "tests/study/study_fixture.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_cli_study {

using namespace crowdlab;
namespace fs = std::filesystem;

namespace {

const char* kLikertYaml = R"(crowdlab: 1
name: study-cli-test
seed: 77
factors:
  method: [baseline, ours]
  viewpoint: [V1, V3]
protocol:
  type: likert
  scale: {points: 6, labels: ["I strongly disagree", "I fully agree"]}
  instructions: "You will watch short videos of crowds. Answer the six statements below each video, then press Next."
  inter_trial: {screen: fixation, min_ms: 300}
  min_view_ms: 1200
  questions:
    - {id: Q1, text: "Contacts made by characters between them seem natural to me"}
    - {id: Q2, text: "Character bodies overlap, it is not physically realistic to me", reverse: true}
    - {id: Q3, text: "Characters seem to make contact and sometimes push one another"}
    - {id: Q4, text: "Characters move as if they were alone, their motion ignore neighbors", reverse: true}
    - {id: Q5, text: "A crowd moving like this one could exist in the real life"}
    - {id: Q6, text: "I feel this crowd as a whole does not move in a natural way", reverse: true}
  composites:
    - {id: Q_CR, items: [Q1, Q2]}
    - {id: Q_CA, items: [Q3, Q4]}
    - {id: Q_OR, items: [Q5, Q6]}
)";

const char* kAfcYaml = R"(crowdlab: 1
name: study-cli-2afc
seed: 5
factors:
  shoulder: [0]
  distance: [0.35]
protocol:
  type: 2afc
  scale: {points: 7, labels: ["not very natural", "very natural"]}
  loop_video: false
  questions:
    - {id: collision, kind: yesno, text: "Did the characters go through each other?"}
    - {id: naturalness, text: "How natural was the interaction?"}
)";

using crowdlab::test::slurp;

fs::path write_text(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
  return p;
}

fs::path likert_script(const fs::path& dir, const StimulusManifest& m) {
  std::string s = "stimulus,question,response\n";
  int n = 0;
  for (const auto& e : m.entries)
    for (int q = 1; q <= 6; ++q)
      s += e.id + ",Q" + std::to_string(q) + "," + std::to_string(1 + (n++ % 6)) + "\n";
  return write_text(dir / "script.csv", s);
}

/// (trial, question) -> stimulus|response, requiring no duplicates.
std::map<std::pair<std::string, std::string>, std::string> answers(const fs::path& csv) {
  const CsvTable t = read_csv(csv.string());
  std::map<std::pair<std::string, std::string>, std::string> out;
  for (size_t r = 0; r < t.rows.size(); ++r)
    REQUIRE(out.emplace(std::make_pair(t.cell(r, t.column("trial")), t.cell(r, t.column("question"))),
                        t.cell(r, t.column("stimulus")) + "|" + t.cell(r, t.column("response")))
                .second);
  return out;
}

bool have_tool(const std::string& name) {
  return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

}  // namespace

TEST_CASE("crowdlab study --responses: a scripted session, used ids refused, corrupted stimuli caught",
          "[study]") {
  const auto dir = test::scratch_dir("study-cli");
  const auto m =
      test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}});
  const auto spec = write_text(dir / "spec.yaml", kLikertYaml);
  const auto script = likert_script(dir, m);
  const std::vector<std::string> base = {"study",         spec.string(),
                                         "--participant", "P07",
                                         "--stimuli",     (dir / "stimuli").string(),
                                         "--out",         (dir / "out").string(),
                                         "--responses",   script.string()};
  auto r = test::run_cli(base);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(answers(dir / "out" / "P07.csv").size() == 4 * 6);
  r = test::run_cli(base);  // used id
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--resume") != std::string::npos);
  auto resume = base;
  resume.push_back("--resume");
  CHECK(test::run_cli(resume).exit_code == 0);
  CHECK(answers(dir / "out" / "P07.csv").size() == 4 * 6);
  // --resume of an id with no session (a typo) is refused, and starts nothing.
  auto typo = resume;
  typo[3] = "P70";
  r = test::run_cli(typo);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("no session") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out" / "P70.csv"));
  CHECK_FALSE(fs::exists(dir / "out" / "P70.json"));
  // Ids differing only in case clash (one file on case-insensitive disks, one person to a reader).
  auto lower = base;
  lower[3] = "p07";
  r = test::run_cli(lower);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("P07") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out" / "p07.csv"));
  // The id pattern: letters, digits, _ and -, starting with a letter or digit.
  for (const std::string& bad :
       std::vector<std::string>{"../P1", "P 1", "P.1", "_P1", std::string(65, 'a')}) {
    auto b = base;
    b[3] = bad;
    r = test::run_cli(b);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--participant") != std::string::npos);
  }
  // A truncated clip: refused before the session starts, nothing written.
  fs::resize_file(dir / "stimuli" / m.entries[2].file, 100);
  auto other = base;
  other[3] = "P08";
  r = test::run_cli(other);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("sha256 mismatch") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out" / "P08.csv"));
  // The same for a window session: refused before the window opens (here there is no display at
  // all, so reaching the window would fail with "no display" instead).
  const std::string window_cmd =
      "env -u DISPLAY -u WAYLAND_DISPLAY " + test::shell_quote(test::crowdlab_exe().string()) + " study " +
      spec.string() + " --participant P09 --stimuli " + (dir / "stimuli").string() + " --out " +
      (dir / "out").string() + " 2> " + (dir / "window.err").string();
  const int window_rc = std::system(window_cmd.c_str());
  CHECK(WIFEXITED(window_rc));
  CHECK(WEXITSTATUS(window_rc) == 2);
  CHECK(slurp(dir / "window.err").find("sha256 mismatch") != std::string::npos);
  CHECK(test::run_cli({"study", "--help"}).exit_code == 0);
}

TEST_CASE(
    "simulated answers (--simulate) go to their own folder with simulated = 1, and analyze refuses a mix",
    "[study]") {
  const auto dir = test::scratch_dir("study-simulated");
  const auto m =
      test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}});
  const auto spec = write_text(dir / "spec.yaml", kLikertYaml);
  const std::string stimuli = (dir / "stimuli").string();
  auto r = test::run_cli(
      {"-q", "study", spec.string(), "--participant", "S01", "--stimuli", stimuli, "--simulate", "default"});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_FALSE(fs::exists(dir / "stimuli" / "responses" / "S01.csv"));
  const fs::path sim_csv = dir / "stimuli" / "responses-simulated" / "S01.csv";
  const CsvTable sim = read_csv(sim_csv.string());
  REQUIRE(sim.has_column("simulated"));
  for (size_t i = 0; i < sim.rows.size(); ++i) CHECK(sim.cell(i, sim.column("simulated")) == "1");
  r = test::run_cli({"-q", "study", spec.string(), "--participant", "P01", "--stimuli", stimuli,
                     "--responses", likert_script(dir, m).string()});
  REQUIRE(r.exit_code == 0);
  const fs::path real_csv = dir / "stimuli" / "responses" / "P01.csv";
  const CsvTable real = read_csv(real_csv.string());
  for (size_t i = 0; i < real.rows.size(); ++i) CHECK(real.cell(i, real.column("simulated")) == "0");
  // One CSV holding both (as a careless merge makes): refused, unless asked for.
  std::string merged = slurp(real_csv);
  const std::string sim_text = slurp(sim_csv);
  merged += sim_text.substr(sim_text.find('\n') + 1);
  const auto merged_csv = write_text(dir / "merged.csv", merged);
  const std::vector<std::string> anova = {"analyze",  "anova",    "--csv",     merged_csv.string(),
                                          "--dv",     "response", "--subject", "participant",
                                          "--within", "method"};
  r = test::run_cli(anova);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--allow-simulated-mix") != std::string::npos);
  auto allowed = anova;
  allowed.push_back("--allow-simulated-mix");
  r = test::run_cli(allowed);
  CHECK(r.err.find("--allow-simulated-mix") == std::string::npos);
  // A report over a folder holding both response folders.
  fs::create_directories(dir / "study");
  fs::copy(dir / "stimuli" / "responses", dir / "study" / "responses", fs::copy_options::recursive);
  fs::copy(dir / "stimuli" / "responses-simulated", dir / "study" / "sim", fs::copy_options::recursive);
  const std::vector<std::string> report = {"analyze",     "report", (dir / "study").string(), "--spec",
                                           spec.string(), "--out",  (dir / "report").string()};
  r = test::run_cli(report);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--allow-simulated-mix") != std::string::npos);
}

TEST_CASE("the study window's spec keys are validated with file, line and key", "[study]") {
  const auto dir = test::scratch_dir("study-window-keys");
  struct Bad {
    std::string yaml, key;
  };
  const std::vector<Bad> bad = {{"  inter_trial: {screen: cross}\n", "protocol.inter_trial.screen"},
                                {"  inter_trial: {min_ms: -5}\n", "protocol.inter_trial.min_ms"},
                                {"  inter_trial: {wait: 3}\n", "protocol.inter_trial.wait"},
                                {"  video_share: 0.1\n", "protocol.video_share"},
                                {"  video_share: 0.97\n", "protocol.video_share"}};
  for (const Bad& b : bad) {
    const auto spec = write_text(dir / "spec.yaml", std::string(kAfcYaml) + b.yaml);
    const auto r = test::run_cli({"validate", spec.string()});
    INFO(b.yaml << r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("spec.yaml:14") != std::string::npos);
    CHECK(r.err.find(b.key) != std::string::npos);
  }
  const auto good = write_text(dir / "good.yaml", std::string(kAfcYaml) +
                                                      "  inter_trial: {screen: blank, min_ms: 800}\n"
                                                      "  video_share: 0.6\n"
                                                      // validate also refuses a crowd without a size, as
                                                      // run does (issue 30)
                                                      "scenario: {agents: 2}\n");
  CHECK(test::run_cli({"validate", good.string()}).exit_code == 0);
}

TEST_CASE("SIGKILL during a session, then --resume: complete, no duplicates, same answers", "[study]") {
  const auto dir = test::scratch_dir("study-kill");
  const auto m =
      test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}}, 2);
  const auto spec = write_text(dir / "spec.yaml", kLikertYaml);
  const auto script = likert_script(dir, m);
  auto args = [&](const fs::path& out) {
    return std::vector<std::string>{
        "-q",    "study",      spec.string(), "--participant", "P11", "--stimuli", (dir / "stimuli").string(),
        "--out", out.string(), "--responses", script.string()};
  };
  REQUIRE(test::run_cli(args(dir / "reference")).exit_code == 0);
  const auto expected = answers(dir / "reference" / "P11.csv");
  REQUIRE(expected.size() == 6 * 6);

  // A slow participant (300 ms per trial) killed after two trials are on disk.
  auto slow = args(dir / "killed");
  slow.insert(slow.end(), {"--response-delay-ms", "300"});
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    std::vector<char*> argv;
    std::string exe = test::crowdlab_exe().string();
    argv.push_back(exe.data());
    for (auto& a : slow) argv.push_back(a.data());
    argv.push_back(nullptr);
    freopen("/dev/null", "w", stderr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  const fs::path csv = dir / "killed" / "P11.csv";
  bool two_trials = false;
  // Up to 60 s: under the sanitizers on a loaded machine the session can take several seconds to start.
  for (int i = 0; i < 6000 && !two_trials; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const std::string text = fs::exists(csv) ? slurp(csv) : "";
    two_trials = std::count(text.begin(), text.end(), '\n') >= 1 + 2 * 6;
  }
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  REQUIRE(two_trials);
  CHECK(WIFSIGNALED(status));
  const size_t rows_before = answers(csv).size();
  CHECK(rows_before < 6 * 6);  // really interrupted
  // Simulate a torn write on top: half a row at the end.
  std::ofstream(csv, std::ios::app) << "P11,1,practi";
  auto resume = args(dir / "killed");
  resume.push_back("--resume");
  const auto r = test::run_cli(resume);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(answers(csv) == expected);
  CHECK(slurp(csv).back() == '\n');
  CHECK(slurp(csv.string() + ".recovered").ends_with("P11,1,practi"));  // the cut bytes, kept aside
  const std::string meta = slurp(dir / "killed" / "P11.json");
  CHECK(meta.find("\"complete\"") != std::string::npos);
  CHECK(meta.find("\"interrupted\"") != std::string::npos);  // the killed run
}

TEST_CASE("crowdlab simulate-study and power", "[study]") {
  const auto dir = test::scratch_dir("study-cli-sim");
  test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}});
  const auto spec = write_text(dir / "spec.yaml", kLikertYaml);
  auto r = test::run_cli({"-q", "simulate-study", spec.string(), "--stimuli", (dir / "stimuli").string(),
                          "--observers", "4", "--out", (dir / "sim").string(), "--seed", "9"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(read_csv((dir / "sim" / "responses.csv").string()).rows.size() == 4u * 4u * 6u);
  r = test::run_cli({"-q", "power", spec.string(), "--stimuli", (dir / "stimuli").string(), "--contrast",
                     "method:baseline,ours", "--effect", "1.0", "--dv", "Q_CR", "--n", "4,12",
                     "--simulations", "40", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("\"power\"") != std::string::npos);
  CHECK(test::run_cli({"power", spec.string(), "--stimuli", (dir / "stimuli").string(), "--contrast", "nope"})
            .exit_code == 2);
  // Issue 33: "4.5" and "12abc" were read as 4 and 12 (std::stoi stops at the first non-digit), silently.
  for (const std::string n : {"4.5", "12abc"}) {
    const auto bad = test::run_cli({"-q", "power", spec.string(), "--stimuli", (dir / "stimuli").string(),
                                    "--contrast", "method:baseline,ours", "--n", n, "--simulations", "2"});
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.err, Catch::Contains("--n") && Catch::Contains("not an integer: '" + n + "'"));
  }
}

TEST_CASE("participant test: the real window under Xvfb, driven by xdotool, killed and resumed",
          "[study][window]") {
  if (!have_tool("Xvfb") || !have_tool("xdotool")) {
    WARN("skipping: Xvfb or xdotool not installed");
    return;
  }
  const auto dir = test::scratch_dir("study-window");
  const auto m =
      test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}});
  test::make_stimuli(dir / "afc", {{"shoulder", {"0"}}, {"distance", {"0.35"}}});
  const auto likert = write_text(dir / "likert.yaml", kLikertYaml);
  const auto afc = write_text(dir / "afc.yaml", kAfcYaml);
  // Click targets of the Likert screen, as the window lays them out at 1280x720.
  ProtocolSpec p;
  const auto layout = study::layout_trial_screen({1280, 720}, study::resolve_questions(p));
  std::string targets;
  for (const auto& t : layout.targets)
    targets += std::to_string(t.question) + " " + std::to_string(t.value) + " " +
               std::to_string(t.rect.x + t.rect.width / 2) + " " +
               std::to_string(t.rect.y + t.rect.height / 2) + "\n";
  write_text(dir / "targets.txt", targets);
  // Both sessions write to one output folder; each spec has its own stimuli.
  const std::string cmd =
      test::shell_quote((test::source_dir() / "tests/study/drive_window_session.sh").string()) + " " +
      test::shell_quote(test::crowdlab_exe().string()) + " " + likert.string() + " " +
      (dir / "stimuli").string() + " " + afc.string() + " " + (dir / "afc").string() + " " +
      (dir / "out").string() + " " + (dir / "snap").string() + " " + (dir / "targets.txt").string() + " " +
      " > " + (dir / "drive.log").string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  INFO(slurp(dir / "drive.log"));
  REQUIRE(rc == 0);
  // Likert: all four trials, each once, the answers given by keys and clicks, across the kill.
  const auto got = answers(dir / "out" / "W01.csv");
  CHECK(got.size() == 4 * 6);
  const CsvTable t = read_csv((dir / "out" / "W01.csv").string());
  std::map<std::string, std::string> trial1, trial2, trial4;
  std::set<std::string> sessions;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const std::string trial = t.cell(r, t.column("trial")), q = t.cell(r, t.column("question"));
    if (trial == "1") trial1[q] = t.cell(r, t.column("response"));
    if (trial == "2") trial2[q] = t.cell(r, t.column("response"));
    if (trial == "4") trial4[q] = t.cell(r, t.column("response"));
    sessions.insert(t.cell(r, t.column("session")));
    // Nothing is accepted before the minimum viewing time (min_view_ms: 1200): the keys typed at once
    // after each onset answered nothing.
    CHECK(std::stod(t.cell(r, t.column("rt_ms"))) >= 1200.0);
    // The measured inter-trial gap respects the spec's minimum; the onset is logged.
    CHECK(std::stod(t.cell(r, t.column("inter_trial_ms"))) >= 300.0);
    CHECK(t.cell(r, t.column("onset_utc")).size() == 24);
    // Playback timing per trial: frames and the intervals between them (30 fps clips: 33.3 ms).
    CHECK(std::stol(t.cell(r, t.column("frames_shown"))) > 1);
    CHECK(std::stol(t.cell(r, t.column("frames_dropped"))) >= 0);
    const double mean = std::stod(t.cell(r, t.column("frame_interval_mean_ms")));
    const double p99 = std::stod(t.cell(r, t.column("frame_interval_p99_ms")));
    const double max = std::stod(t.cell(r, t.column("frame_interval_max_ms")));
    CHECK(mean > 5.0);
    CHECK(mean <= p99);
    CHECK(p99 <= max);
  }
  CHECK(trial1 == std::map<std::string, std::string>{
                      {"Q1", "4"}, {"Q2", "2"}, {"Q3", "5"}, {"Q4", "1"}, {"Q5", "6"}, {"Q6", "3"}});
  CHECK(trial2 == std::map<std::string, std::string>{
                      {"Q1", "6"}, {"Q2", "1"}, {"Q3", "4"}, {"Q4", "2"}, {"Q5", "6"}, {"Q6", "1"}});
  // The 3 typed before trial 4's onset answered nothing: trial 4 holds only the keys typed after it.
  CHECK(trial4 == std::map<std::string, std::string>{
                      {"Q1", "1"}, {"Q2", "6"}, {"Q3", "1"}, {"Q4", "6"}, {"Q5", "1"}, {"Q6", "6"}});
  CHECK(sessions == std::set<std::string>{"1", "2"});  // trials 3-4 answered after the resume
  CHECK(fs::exists(dir / "snap" / "W01" / "trial_2_inter_trial.png"));
  const auto afc_rows = answers(dir / "out" / "A01.csv");
  CHECK(afc_rows.at({"1", "collision"}).ends_with("|1"));
  CHECK(afc_rows.at({"1", "naturalness"}).ends_with("|5"));
  (void)m;
}

TEST_CASE("full screen on an X server without a window manager covers the real screen", "[study][window]") {
  if (!have_tool("Xvfb") || !have_tool("xdotool") || !have_tool("xwd")) {
    WARN("skipping: Xvfb, xdotool or xwd not installed");
    return;
  }
  const auto dir = test::scratch_dir("study-fullscreen");
  test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}});
  const auto spec = write_text(dir / "likert.yaml", kLikertYaml);
  // 1600x900: neither the 1280x720 fallback nor anything the window would pick by itself.
  const std::string cmd =
      test::shell_quote((test::source_dir() / "tests/study/fullscreen_window.sh").string()) + " " +
      test::shell_quote(test::crowdlab_exe().string()) + " " + spec.string() + " " +
      (dir / "stimuli").string() + " " + (dir / "out").string() + " " + (dir / "snap").string() +
      " 1600x900 > " + (dir / "drive.log").string() + " 2>&1";
  const int rc = std::system(cmd.c_str());
  INFO(slurp(dir / "drive.log"));
  REQUIRE(rc == 0);
  const std::string geometry = slurp(dir / "out" / "geometry.txt");
  INFO(geometry);
  CHECK(geometry.find("X=0\n") != std::string::npos);
  CHECK(geometry.find("Y=0\n") != std::string::npos);
  CHECK(geometry.find("WIDTH=1600\n") != std::string::npos);
  CHECK(geometry.find("HEIGHT=900\n") != std::string::npos);
  const cv::Mat first = cv::imread((dir / "snap" / "screen_instructions.png").string());
  CHECK(first.cols == 1600);
  CHECK(first.rows == 900);
  // --require-fullscreen is for the window only.
  CHECK(test::run_cli({"study", spec.string(), "--participant", "F02", "--stimuli",
                       (dir / "stimuli").string(), "--require-fullscreen", "--windowed", "800x600"})
            .exit_code == 2);
}

}  // namespace test_cli_study
