#pragma once
// The pass/fail record of a paper reproduction: every quantitative claim it checks, with the value
// measured, the accepted range (its tolerance, stated relative to the paper's value or the paper's
// qualitative claim) and where that range comes from. Written as DIR/checks.json and as a Markdown
// table; finish() throws RuntimeError (exit code 1) when any check failed, after everything is written,
// so CI fails while the outputs stay inspectable.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace crowdlab::cli {

struct ReproductionCheck {
  std::string id;     ///< stable key, e.g. "fig3.stationary.reduction@6.66"
  std::string claim;  ///< what is checked, in words
  double value = 0;   ///< measured
  double low = 0;     ///< accepted range [low, high]
  double high = 0;
  std::string reference;  ///< the paper's value or statement the range derives from
  bool pass = false;
};

class ReproductionChecks {
 public:
  /// Records value in [low, high] (NaN fails).
  void within(std::string id, std::string claim, double value, double low, double high,
              std::string reference);
  const std::vector<ReproductionCheck>& checks() const { return checks_; }
  bool all_pass() const;
  /// | check | measured | accepted | reference | result |
  std::string markdown() const;
  nlohmann::json to_json() const;
  /// Appends the checks table to the report `md`, writes it to dir/README.md and prints it, writes
  /// dir/checks.json, then throws RuntimeError naming the failed checks when any failed.
  void finish(const std::filesystem::path& dir, const std::string& what, std::string md) const;

 private:
  std::vector<ReproductionCheck> checks_;
};

/// A number for tables: 4 significant digits ("nan" for NaN).
std::string repro_number(double v);

}  // namespace crowdlab::cli
