// The reduced paper reproductions, run as a user would (`crowdlab reproduce <paper> --quick`): they must
// finish, write their figures and tables, and pass every check against the paper's values (the
// tolerances live in experiments/cli/reproduce/reproduce_<paper>.hpp and docs/reproductions.md). The
// test also insists that every documented check was actually made, so dropping one cannot pass silently.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "framework/core/csv.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_reproduce {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  REQUIRE(in.good());
  return nlohmann::json::parse(in);
}

/// Every check in checks.json passed (except Fig. 3 overlap reductions when `exempt_reductions`), and each
/// of `expected` is among them.
void require_checks(const fs::path& dir, const std::set<std::string>& expected,
                    bool exempt_reductions = false) {
  const nlohmann::json j = read_json(dir / "checks.json");
  std::set<std::string> ids;
  for (const auto& c : j.at("checks")) {
    const std::string id = c.at("id").get<std::string>();
    ids.insert(id);
    INFO(c.dump());
    if (!exempt_reductions || id.find(".reduction@") == std::string::npos) CHECK(c.at("pass").get<bool>());
  }
  for (const auto& id : expected) {
    INFO("missing check " << id);
    CHECK(ids.count(id) == 1);
  }
  if (!exempt_reductions) CHECK(j.at("all_pass").get<bool>());
}

}  // namespace

TEST_CASE("reproduce gomez2024 --quick: Fig. 3, Fig. 4, timing and study within tolerance", "[reproduce]") {
  const fs::path dir = scratch_dir("reproduce_gomez2024");
  std::vector<std::string> args = {"-q", "reproduce", "gomez2024", "--quick", "--out", dir.string()};
  // Sanitized builds run 0.3 s clips: too short for the corrector's start-up transient, so there the
  // Fig. 3 reduction checks are exempt (exit code 1 from them is accepted); everything else must pass.
  if (kSanitized) args.insert(args.end(), {"--duration", "0.3", "--observers", "6"});
  const CliResult r = run_cli(args);
  INFO(r.out << r.err);
  REQUIRE((r.exit_code == 0 || (kSanitized && r.exit_code == 1)));
  // Fig. 3: one row per scenario x density x method (2 x 5 x 2), ours never above baseline.
  const CsvTable fig3 = read_csv((dir / "fig3" / "overlap_vs_density.csv").string());
  REQUIRE(fig3.rows.size() == 20);
  CHECK(fs::exists(dir / "fig3" / "overlap_vs_density_stationary.png"));
  CHECK(fs::exists(dir / "fig4" / "damping.png"));
  CHECK(read_csv((dir / "timing.csv").string()).rows.size() == 2);
  CHECK(fs::exists(dir / "study_report" / "report.md"));
  // The 1 s clips leave the mesh-level measures out (checked on 20 s clips only; they were about three
  // quarters of this test's metrics stages, issue 31): their columns stay empty.
  const CsvTable quality = read_csv((dir / "correction_quality.csv").string());
  REQUIRE(quality.rows.size() == 20);
  for (const char* column : {"mesh_overlap_fraction", "proxy_coverage"})
    for (const auto& row : quality.rows) CHECK(row.at(quality.column(column)).empty());
  std::set<std::string> expected = {"fig4.push_moves", "fig4.d0_vs_d0.006", "fig4.d0.6_vs_d0.006",
                                    "fig3.stationary.baseline_growth", "fig3.corridor.baseline_growth"};
  for (const char* scenario : {"stationary", "corridor"})
    for (const char* d : {"2.22", "3.33", "4.44", "5.55", "6.66"})
      for (const char* check :
           {"fig3.{s}.reduction@{d}", "quality.{s}@{d}.foot_pops", "quality.{s}@{d}.stance_drift_p99_m",
            "quality.{s}@{d}.rotation_dev_mean_deg", "quality.{s}@{d}.free_limb_dev_p99_deg",
            "quality.{s}@{d}.free_limb_dev_max_deg"}) {
        std::string id = check;
        id.replace(id.find("{s}"), 3, scenario);
        id.replace(id.find("{d}"), 3, d);
        expected.insert(id);
      }
  for (const char* q : {"Q_CR", "Q_CA", "Q_OR"}) {
    expected.insert(std::string("study.") + q + ".method_p");
    expected.insert(std::string("study.") + q + ".ours_minus_baseline");
  }
  require_checks(dir, expected, kSanitized);
}

TEST_CASE("reproduce hoyet2016 --quick: Fig. 3, Table 1 and Table 2 within tolerance", "[reproduce]") {
  const fs::path dir = scratch_dir("reproduce_hoyet2016");
  std::vector<std::string> args = {"-q", "reproduce", "hoyet2016", "--quick", "--out", dir.string()};
  if (kSanitized) args.insert(args.end(), {"--fps", "15", "--duration", "4"});
  const CliResult r = run_cli(args);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  // Fig. 3: 3 shoulder conditions x 11 distances.
  CHECK(read_csv((dir / "fig3" / "volume_vs_distance.csv").string()).rows.size() == 33);
  // Table 1: D_crit and V_crit (checked) and V_crit by the paper's method (reported), 3 conditions each.
  CHECK(read_csv((dir / "table1" / "thresholds.csv").string()).rows.size() == 9);
  // Table 2: 2 scenarios x 5 densities.
  CHECK(read_csv((dir / "table2" / "collisions.csv").string()).rows.size() == 10);
  std::set<std::string> expected = {"fig3.shoulder_motions_reduce_volume", "table2.A.grows_with_density",
                                    "table2.B.grows_with_density", "table2.B_over_A@2.8"};
  for (const char* s : {"0", "1", "2"}) {
    expected.insert(std::string("fig3.shoulder") + s + ".falls_with_distance");
    expected.insert(std::string("fig3.shoulder") + s + ".none_at_0.70");
    expected.insert(std::string("table1.D_crit.shoulder") + s);
    expected.insert(std::string("table1.V_crit.shoulder") + s);
  }
  if (!kSanitized)  // the paper's 10 s clips: absolute counts against Table 2
    for (const char* id :
         {"table2.B@1.vs_paper", "table2.B@1.6.vs_paper", "table2.B@2.8.vs_paper", "table2.A@2.8.vs_paper"})
      expected.insert(id);
  require_checks(dir, expected);
}

TEST_CASE("bad reproduce arguments exit with code 2", "[reproduce]") {
  CHECK(run_cli({"reproduce", "nosuchpaper", "--out", "x"}).exit_code == 2);
  CHECK(run_cli({"reproduce", "gomez2024"}).exit_code == 2);
  CHECK(run_cli({"reproduce", "hoyet2016", "--out", "x", "--observers", "1"}).exit_code == 2);
}

}  // namespace test_reproduce
