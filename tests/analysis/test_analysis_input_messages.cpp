// Issue 33: analysis inputs that ended in a library's bare message ("stod", bad_alloc, a 300-digit range)
// or in a message against a derived table now name the file, row and column (or the option), exit 2.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/analysis/reference_table.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_analysis_input_messages {

using namespace crowdlab;
using crowdlab::test::analysis_data;
using crowdlab::test::run_cli;
namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A copy of `data` with the first occurrence of `from` replaced by `to`.
fs::path edited_copy(const std::string& data, const fs::path& out, const std::string& from,
                     const std::string& to) {
  std::string text = read_text(analysis_data(data));
  REQUIRE(text.find(from) != std::string::npos);
  text.replace(text.find(from), from.size(), to);
  std::ofstream(out) << text;
  return out;
}

/// A Likert study of 4 participants x 4 stimuli x the demo spec's 6 questions, one answer replaced.
fs::path likert_study(const fs::path& dir, const std::string& replaced_reverse_coded) {
  fs::create_directories(dir);
  std::ofstream out(dir / "responses.csv");
  out << "participant,session,trial,stimulus,density,viewpoint,method,question,response,reverse_coded,"
         "practice\n";
  int row = 0;
  for (int p = 1; p <= 4; ++p)
    for (const char* density : {"3.33", "6.66"})
      for (const char* method : {"baseline", "ours"})
        for (int q = 1; q <= 6; ++q) {
          const int v = 1 + (p + q + (method[0] == 'o' ? 2 : 0)) % 6;
          const std::string coded = ++row == 9 ? replaced_reverse_coded : std::to_string(q % 2 ? v : 7 - v);
          out << p << ",1,1,s_" << density << "_" << method << "," << density << ",V1," << method << ",Q" << q
              << "," << v << "," << coded << ",0\n";
        }
  return dir;
}

}  // namespace

TEST_CASE("analysis: a rating outside the range of a double is named, not 'stod'", "[analysis][cli]") {
  const auto dir = test::scratch_dir("issue33-clmm");
  const auto csv = edited_copy("likert_crossed.csv", dir / "tiny.csv", "p1,s1,baseline,1,2\n",
                               "p1,s1,baseline,1,1e-400\n");
  const auto r =
      run_cli({"analyze", "clmm", "--csv", csv.string(), "--formula", "rating ~ method + (1 | participant)"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("tiny.csv:2:5: column 'rating'") && Catch::Contains("1e-400"));
}

TEST_CASE("analysis: report names the response file for a tiny reverse_coded value or a huge answer",
          "[analysis][cli]") {
  const auto base = test::scratch_dir("issue33-report");
  const std::string spec = (test::source_dir() / "experiments" / "demo.yaml").string();
  for (const std::string value : {"1e-320", "1.7e308"}) {
    INFO(value);
    const auto study = likert_study(base / ("study" + value), value);
    const auto r = run_cli(
        {"analyze", "report", study.string(), "--spec", spec, "--out", (base / ("out" + value)).string()});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("responses.csv:10:10: column 'reverse_coded'") &&
                          Catch::Contains("off its 1-"));
  }
}

TEST_CASE("analysis: a formula over missing columns is refused before it is expanded", "[analysis][cli]") {
  std::string crossed;
  for (int i = 0; i < 24; ++i) crossed += (i ? "*" : "") + std::string("m") + std::to_string(i);
  for (const char* command : {"lmm", "clmm"}) {
    const auto r = run_cli({"analyze", command, "--csv", analysis_data("lmm_flat.csv"), "--formula",
                            "y ~ " + crossed + " + (1 | participant)"});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Catch::Contains("lmm_flat.csv:1: the formula names 24 columns the file lacks: 'm0', "
                                      "'m1'") &&
                          Catch::Contains("(its columns: 'participant', 'cond', 'rep', 'y')"));
  }
}

TEST_CASE("analysis: an option's range is stated as a person would, not in 300 digits", "[analysis][cli]") {
  const std::vector<std::string> anova = {"analyze",  "anova",      "--csv",     analysis_data("md_12.1.csv"),
                                          "--dv",     "rt",         "--subject", "id",
                                          "--within", "angle,noise"};
  auto with = [&](std::vector<std::string> extra) {
    auto args = anova;
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args);
  };
  const auto zero = with({"--max-levels", "0"});
  CHECK(zero.exit_code == 2);
  CHECK_THAT(zero.err, Catch::Contains("--max-levels: must be a positive number, got '0'"));
  CHECK(zero.err.size() < 200);
  CHECK_THAT(with({"--max-cells", "-1"}).err, Catch::Contains("--max-cells: must not be negative, got '-1'"));
  const auto threads = run_cli({"--threads", "0", "version"});
  CHECK_THAT(threads.err, Catch::Contains("--threads: must be between 1 and 4096, got '0'"));
}

TEST_CASE("analysis: a random slope of a many-level factor is refused before the fit, with the option",
          "[analysis][cli]") {
  // Issue 33: `(stimulus | participant)` with 30 stimuli (465 covariance parameters) ran for hours.
  const auto dir = test::scratch_dir("issue33-lmm-size");
  const auto csv = dir / "slopes.csv";
  {
    std::ofstream out(csv);
    out << "participant,stimulus,y\n";
    for (int p = 0; p < 40; ++p)
      for (int s = 0; s < 30; ++s)
        for (int r = 0; r < 2; ++r)
          out << "p" << p << ",s" << s << "," << ((p * 7 + s * 3 + r * 5) % 11) << "\n";
  }
  const auto r =
      run_cli({"analyze", "lmm", "--csv", csv.string(), "--formula", "y ~ 1 + (stimulus | participant)"}, 60);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("slopes.csv: the random terms have 465 covariance parameters") &&
                        Catch::Contains("more than the limit of 55") &&
                        Catch::Contains("--max-covariance-parameters"));
  const auto raised = run_cli({"analyze", "lmm", "--csv", csv.string(), "--formula",
                               "y ~ 1 + (stimulus | participant)", "--max-covariance-parameters", "10"});
  CHECK_THAT(raised.err, Catch::Contains("more than the limit of 10"));
}

TEST_CASE("analysis: report refuses participants x items above its limit before any model, with the option",
          "[analysis][cli]") {
  // Issue 33: `analyze report` on 2,000 participants ran for minutes (one mixed model per Likert item, a
  // random intercept per participant each). The demo spec fits 6 items.
  const auto base = test::scratch_dir("issue33-report-limit");
  const std::string spec = (test::source_dir() / "experiments" / "demo.yaml").string();
  const auto study = likert_study(base / "study", "1");  // row 9's own value: a valid study of 4 people
  const auto small = run_cli({"analyze", "report", study.string(), "--spec", spec, "--out",
                              (base / "out").string(), "--max-participant-items", "20"});
  CHECK(small.exit_code == 2);
  CHECK_THAT(small.err, Catch::Contains("4 participants x 6 Likert items") &&
                            Catch::Contains("= 24 participant-items, more than the limit of 20") &&
                            Catch::Contains("--max-participant-items"));
  CHECK_FALSE(fs::exists(base / "out" / "report.md"));
  CHECK_FALSE(fs::exists(base / "out" / "figures"));
  // The study: 2,000 participants under the default limit, refused in about the time it takes to
  // read the answers (it ran for minutes before).
  fs::create_directories(base / "many");
  {
    std::ofstream out(base / "many" / "responses.csv");
    out << "participant,session,trial,stimulus,density,viewpoint,method,question,response,reverse_coded,"
           "practice\n";
    for (int p = 1; p <= 2000; ++p)
      for (const char* method : {"baseline", "ours"})
        for (int q = 1; q <= 6; ++q)
          out << p << ",1,1,s_" << method << ",3.33,V1," << method << ",Q" << q << ",3," << (q % 2 ? 3 : 4)
              << ",0\n";
  }
  const auto many = run_cli(
      {"analyze", "report", (base / "many").string(), "--spec", spec, "--out", (base / "out2").string()},
      120);
  CHECK(many.exit_code == 2);
  CHECK_THAT(many.err, Catch::Contains("2000 participants x 6 Likert items") &&
                           Catch::Contains("limit of 6000") && Catch::Contains("--max-participant-items"));
}

TEST_CASE(
    "analysis: an output folder that cannot be made is named as an input error, not a raw "
    "filesystem_error",
    "[analysis][cli]") {
  // Issue 33 item 4: "crowdlab: error: filesystem error: cannot create directories: Not a directory
  // [afile/sub]", exit 1.
  const auto base = test::scratch_dir("issue33-report-out");
  const std::string spec = (test::source_dir() / "experiments" / "demo.yaml").string();
  const auto study = likert_study(base / "study", "1");
  std::ofstream(base / "afile") << "x";
  const auto out = (base / "afile" / "sub").string();
  const auto r = run_cli({"analyze", "report", study.string(), "--spec", spec, "--out", out});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(out + ": ") && Catch::Contains("Not a directory"));
  CHECK_THAT(r.err, !Catch::Contains("filesystem error:"));
}

TEST_CASE("analysis: psychometric --p reads the whole text of each probability", "[analysis][cli]") {
  // Issue 33: std::stod read "0.5abc" as 0.5 (exit 0), and "nan" was refused without the option's name.
  for (const std::string p : {"0.5abc", "nan", "1"}) {
    const auto r =
        run_cli({"analyze", "psychometric", "--csv", analysis_data("psychometric_trials.csv"), "--subject",
                 "participant", "--x", "distance", "--response", "collision", "--p", "0.25," + p});
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err,
               Catch::Contains("--p: expected probabilities in (0, 1), comma-separated, got '" + p + "'"));
  }
}

}  // namespace test_analysis_input_messages
