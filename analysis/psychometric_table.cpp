#include "analysis/psychometric_table.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "analysis/apa_format.hpp"
#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab::analysis {

std::string probability_key(double p) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", p);
  return buf;
}

PsychometricAnalysis analyze_psychometric(const CsvTable& table, const PsychometricRequest& request) {
  if (request.x_transform != "none" && request.x_transform != "cbrt")
    throw InputError("x transform must be 'none' or 'cbrt', got '" + request.x_transform + "'");
  for (double p : request.probabilities)
    if (!(p > 0 && p < 1)) throw InputError("threshold probabilities must be in (0, 1)");
  const size_t subject_col = table.column(request.subject);
  const size_t x_col = table.column(request.x);
  const size_t y_col = table.column(request.response);
  const bool has_by = !request.by.empty();
  const size_t by_col = has_by ? table.column(request.by) : 0;
  PsychometricAnalysis out;
  out.request = request;
  std::map<std::pair<std::string, std::string>, size_t> index;
  std::vector<std::string> by_levels;
  std::map<std::string, size_t> by_index;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string subject = table.cell(r, subject_col);
    const std::string by = has_by ? table.cell(r, by_col) : "";
    double x = table.number(r, x_col);
    const double y = table.number(r, y_col);
    const SourceLocation where{table.source, table.line_numbers[r], 0, request.response};
    if (y != 0.0 && y != 1.0)
      throw InputError(where, "response must be 0 or 1, got '" + table.cell(r, y_col) + "'");
    if (!std::isfinite(x))
      throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, request.x}, "not finite");
    if (request.x_transform == "cbrt") {
      if (x < 0)
        throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, request.x},
                         "negative volume");
      x = std::cbrt(x);
    }
    auto [it, inserted] = index.emplace(std::make_pair(subject, by), out.fits.size());
    if (inserted) out.fits.push_back(PsychometricRow{subject, by, {}, {}, {}, {}, {}, {}});
    out.fits[it->second].x.push_back(x);
    out.fits[it->second].y.push_back(y);
    if (by_index.emplace(by, by_levels.size()).second) by_levels.push_back(by);
  }
  for (auto& row : out.fits) {
    try {
      row.fit = fit_psychometric(row.x, row.y, request.options);
    } catch (const InputError& e) {
      throw InputError(table.source + ": subject '" + row.subject + "'" +
                       (row.by.empty() ? "" : ", " + request.by + " '" + row.by + "'") + ": " + e.what());
    }
    for (double p : request.probabilities) row.thresholds.push_back(row.fit.threshold(p));
    row.goodness = psychometric_goodness(row.x, row.y, row.fit, row.fit.lapse_fitted ? 3 : 2);
    if (request.bootstrap > 0)
      row.ci = bootstrap_thresholds(row.x, row.fit, request.probabilities, request.bootstrap,
                                    derive_seed(request.seed, row.subject + "/" + row.by), request.options);
  }
  for (const auto& by : by_levels) {
    PsychometricGroup g;
    g.by = by;
    for (size_t k = 0; k < request.probabilities.size(); ++k) {
      std::vector<double> v;
      for (const auto& row : out.fits)
        if (row.by == by && std::isfinite(row.thresholds[k])) v.push_back(row.thresholds[k]);
      double mean = 0, ss = 0;
      for (double t : v) mean += t;
      mean = v.empty() ? std::numeric_limits<double>::quiet_NaN() : mean / static_cast<double>(v.size());
      for (double t : v) ss += (t - mean) * (t - mean);
      g.mean.push_back(mean);
      g.sd.push_back(v.size() > 1 ? std::sqrt(ss / static_cast<double>(v.size() - 1))
                                  : std::numeric_limits<double>::quiet_NaN());
      g.n = v.size();
    }
    out.groups.push_back(g);
  }
  // RM-ANOVA of the thresholds over the conditions, when the design allows it.
  if (by_levels.size() >= 2 && !request.probabilities.empty()) {
    CsvTable t;
    t.source = table.source + " (thresholds at p = " + probability_key(request.probabilities[0]) + ")";
    t.header = {"subject", "condition", "threshold"};
    for (const auto& row : out.fits) {
      if (!std::isfinite(row.thresholds[0])) continue;
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.17g", row.thresholds[0]);
      t.rows.push_back({row.subject, row.by, buf});
      t.line_numbers.push_back(static_cast<int>(t.rows.size()) + 1);
    }
    try {
      out.threshold_anova = rm_anova(build_within_design(t, "threshold", "subject", {"condition"}));
      out.threshold_anova->effects[0].name = request.by;
    } catch (const InputError&) {
      out.threshold_anova
          .reset();  // unbalanced (a subject lacks a condition): no ANOVA, groups still reported
    }
  }
  return out;
}

namespace {
nlohmann::json num(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
}  // namespace

nlohmann::json psychometric_to_json(const PsychometricAnalysis& a) {
  nlohmann::json fits = nlohmann::json::array();
  const auto& probs = a.request.probabilities;
  for (const auto& row : a.fits) {
    nlohmann::json th = nlohmann::json::object(), ci = nlohmann::json::object();
    for (size_t k = 0; k < probs.size(); ++k) {
      th[probability_key(probs[k])] = num(row.thresholds[k]);
      if (!row.ci.empty()) ci[probability_key(probs[k])] = {num(row.ci[k].lower), num(row.ci[k].upper)};
    }
    fits.push_back(
        {{"subject", row.subject},
         {"by", row.by},
         {"intercept", num(row.fit.intercept)},
         {"slope", num(row.fit.slope)},
         {"thresholds", th},
         {"ci", row.ci.empty() ? nlohmann::json(nullptr) : ci},
         {"trials", row.x.size()},
         {"converged", row.fit.converged},
         {"separated", row.fit.separated},
         {"warning", row.fit.warning.empty() ? nlohmann::json(nullptr) : nlohmann::json(row.fit.warning)},
         {"lapse", row.fit.lapse},
         {"lapse_fitted", row.fit.lapse_fitted},
         {"lapse_at_boundary",
          row.fit.lapse_fitted ? nlohmann::json(row.fit.lapse_at_boundary) : nlohmann::json(nullptr)},
         {"step_not_identified", row.fit.step_not_identified},
         {"nll", num(row.fit.nll)},
         {"deviance", num(row.goodness.deviance)},
         {"deviance_df", row.goodness.df},
         {"deviance_p", num(row.goodness.p)},
         {"dispersion", num(row.goodness.dispersion)},
         {"overdispersed", row.goodness.overdispersed}});
  }
  nlohmann::json groups = nlohmann::json::array();
  for (const auto& g : a.groups) {
    nlohmann::json mean = nlohmann::json::object(), sd = nlohmann::json::object();
    for (size_t k = 0; k < probs.size(); ++k) {
      mean[probability_key(probs[k])] = num(g.mean[k]);
      sd[probability_key(probs[k])] = num(g.sd[k]);
    }
    groups.push_back({{"by", g.by}, {"n", g.n}, {"mean", mean}, {"sd", sd}});
  }
  nlohmann::json anova = nullptr;
  if (a.threshold_anova) {
    const auto& e = a.threshold_anova->effects[0];
    anova = {{"effect", e.name},
             {"probability", probs[0]},
             {"df1", e.df1},
             {"df2", e.df2},
             {"F", num(e.f)},
             {"p", num(e.p)},
             {"pes", num(e.pes)},
             {"ges", num(e.ges)},
             {"gg_eps", e.gg_eps ? nlohmann::json(*e.gg_eps) : nlohmann::json(nullptr)},
             {"p_gg", e.p_gg ? nlohmann::json(*e.p_gg) : nlohmann::json(nullptr)}};
  }
  return {{"fits", fits}, {"groups", groups}, {"anova", anova}};
}

std::string psychometric_markdown_table(const PsychometricAnalysis& a, const std::string& unit) {
  std::string s = "| " + (a.request.by.empty() ? std::string("Condition") : a.request.by) + " | n |";
  std::string rule = "|---|---|";
  for (double p : a.request.probabilities) {
    s += " threshold at " + probability_key(p * 100) + " %" + (unit.empty() ? "" : " (" + unit + ")") + " |";
    rule += "---|";
  }
  s += "\n" + rule + "\n";
  char buf[96];
  for (const auto& g : a.groups) {
    s += "| " + (g.by.empty() ? std::string("all") : g.by) + " | " + std::to_string(g.n) + " |";
    for (size_t k = 0; k < g.mean.size(); ++k) {
      // A group whose participants all lack a finite threshold (flat or separated answers that never
      // cross p) has no mean: "Not fitted"; one threshold alone has no SD (issue 32).
      if (!std::isfinite(g.mean[k]))
        std::snprintf(buf, sizeof buf, " Not fitted: no finite threshold |");
      else if (!std::isfinite(g.sd[k]))
        std::snprintf(buf, sizeof buf, " %.3f (one participant, no SD) |", g.mean[k]);
      else
        std::snprintf(buf, sizeof buf, " %.3f ± %.3f |", g.mean[k], g.sd[k]);
      s += buf;
    }
    s += "\n";
  }
  if (a.threshold_anova)
    s += "\nRM-ANOVA of the thresholds: " + apa_f_sentence(a.threshold_anova->effects[0]) + "\n";
  return s;
}

}  // namespace crowdlab::analysis
