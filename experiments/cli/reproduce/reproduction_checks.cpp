#include "experiments/cli/reproduce/reproduction_checks.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>

#include "framework/core/error.hpp"
#include "framework/pipeline/provenance.hpp"

namespace crowdlab::cli {

void ReproductionChecks::within(std::string id, std::string claim, double value, double low, double high,
                                std::string reference) {
  const bool pass = std::isfinite(value) && value >= low && value <= high;
  spdlog::log(pass ? spdlog::level::info : spdlog::level::warn, "check {}: {} = {} (accepted [{}, {}]) {}",
              id, claim, repro_number(value), repro_number(low), repro_number(high), pass ? "pass" : "FAIL");
  checks_.push_back({std::move(id), std::move(claim), value, low, high, std::move(reference), pass});
}

bool ReproductionChecks::all_pass() const {
  for (const auto& c : checks_)
    if (!c.pass) return false;
  return true;
}

std::string repro_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.4g}", v);
}

std::string ReproductionChecks::markdown() const {
  std::string md =
      "| check | claim | measured | accepted | reference | result |\n|---|---|---|---|---|---|\n";
  for (const auto& c : checks_)
    md += fmt::format("| `{}` | {} | {} | [{}, {}] | {} | {} |\n", c.id, c.claim, repro_number(c.value),
                      repro_number(c.low), repro_number(c.high), c.reference, c.pass ? "pass" : "**FAIL**");
  return md;
}

nlohmann::json ReproductionChecks::to_json() const {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& c : checks_)
    j.push_back({{"id", c.id},
                 {"claim", c.claim},
                 {"value", std::isfinite(c.value) ? nlohmann::json(c.value) : nlohmann::json()},
                 {"low", c.low},
                 {"high", c.high},
                 {"reference", c.reference},
                 {"pass", c.pass}});
  return j;
}

void ReproductionChecks::finish(const std::filesystem::path& dir, const std::string& what,
                                std::string md) const {
  md += "## Checks\n\n" + markdown();
  write_file_atomic(dir / "README.md", md);
  std::printf("%s\nreproduction report: %s\n", md.c_str(), (dir / "README.md").c_str());
  nlohmann::json j = {{"reproduction", what}, {"all_pass", all_pass()}, {"checks", to_json()}};
  write_file_atomic(dir / "checks.json", j.dump(2) + "\n");
  std::string failed;
  for (const auto& c : checks_)
    if (!c.pass) failed += (failed.empty() ? "" : ", ") + c.id;
  if (!failed.empty())
    throw RuntimeError(what + ": results outside their stated tolerance: " + failed + " (see " +
                       (dir / "checks.json").string() + ")");
}

}  // namespace crowdlab::cli
