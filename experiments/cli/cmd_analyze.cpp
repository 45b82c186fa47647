// `crowdlab analyze anova|posthoc|psychometric|report`: statistics from response CSVs without R.
// The flags and the --json shapes are a stable interface for scripts (see analysis/analysis_json.hpp
// and analysis/psychometric_table.hpp).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "analysis/analysis_json.hpp"
#include "analysis/apa_format.hpp"
#include "analysis/posthoc.hpp"
#include "analysis/psychometric_table.hpp"
#include "analysis/rm_anova.hpp"
#include "analysis/simulated_rows.hpp"
#include "analysis/study_report.hpp"
#include "experiments/cli/command_registry.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::cli {
namespace {
using namespace crowdlab::analysis;

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

struct DesignArgs {
  std::string csv, dv, subject, within;
  DesignLimits limits;
  bool allow_simulated_mix = false;
};

constexpr const char* kAllowMixHelp =
    "Analyse real and simulated rows (column `simulated`) together; refused by default (exit 2)";

/// Reads a CSV and refuses a mix of real and simulated rows unless allowed.
CsvTable read_unmixed_csv(const std::string& path, bool allow_mix) {
  CsvTable table = read_csv(path);
  SimulatedRows mix;
  mix.add(table);
  mix.check(allow_mix);
  return table;
}

/// The same over every response CSV under a study folder (what `analyze report` reads).
void check_study_dir_unmixed(const std::string& dir, bool allow_mix) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(dir)) return;  // the report gives the error
  SimulatedRows mix;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".csv") {
      const CsvTable table = read_csv(entry.path().string());
      if (table.has_column("participant")) mix.add(table);  // a response log, not e.g. a manifest
    }
  mix.check(allow_mix);
}

void add_design_options(CLI::App* cmd, DesignArgs& a) {
  cmd->add_option("--csv", a.csv, "Tidy CSV: one row per trial (repetitions are averaged per cell)")
      ->required();
  cmd->add_option("--dv", a.dv, "Dependent-variable column (numeric)")->required();
  cmd->add_option("--subject", a.subject, "Subject (participant) column")->required();
  cmd->add_option("--within", a.within, "Within-subject factor columns, comma-separated (e.g. A,B,C)")
      ->required();
  cmd->add_option(
         "--max-levels", a.limits.max_levels,
         "Refuse (exit 2) a factor with more levels than this, before any work (see docs/analysis.md)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-cells", a.limits.max_cells,
                  "Refuse (exit 2) a design with more cells (product of the levels) than this")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--allow-simulated-mix", a.allow_simulated_mix, kAllowMixHelp);
}

struct AnovaOptions {
  DesignArgs design;
  bool json = false;
};

struct PosthocOptions {
  DesignArgs design;
  std::string effect, method = "tukey";
  bool json = false, simple = false;
  size_t max_comparisons = kDefaultMaxComparisons;
};

struct PsychometricOptions {
  PsychometricRequest request;
  std::string csv, probabilities = "0.5,0.05";
  bool json = false, allow_simulated_mix = false;
};

struct ReportOptions {
  std::string study_dir, spec_path, out_dir;
  bool allow_simulated_mix = false;
};

WithinDesign load_design(const DesignArgs& a) {
  const auto within = split_list(a.within);
  if (within.empty()) throw InputError("--within: no factor given");
  return build_within_design(read_unmixed_csv(a.csv, a.allow_simulated_mix), a.dv, a.subject, within,
                             a.limits);
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto* analyze =
      root.add_subcommand("analyze", "Statistics: RM-ANOVA, post-hoc tests, psychometric fits, reports");
  analyze->require_subcommand(1);

  // ---- anova ----
  auto anova_opt = std::make_shared<AnovaOptions>();
  auto* anova = analyze->add_subcommand(
      "anova",
      "Repeated-measures ANOVA (all within-subject factors) with Mauchly's test, Greenhouse-Geisser and "
      "Huynh-Feldt corrections, partial and generalised eta squared");
  add_design_options(anova, anova_opt->design);
  anova->add_flag(
      "--json", anova_opt->json,
      "Print {\"effects\": [{\"effect\", \"df1\", \"df2\", \"F\", \"p\", \"pes\", \"ges\", \"mauchly_W\", "
      "\"mauchly_p\", \"gg_eps\", \"hf_eps\", \"p_gg\", \"p_hf\", ...}]} (null where not applicable)");
  anova->callback([o = anova_opt] {
    const auto result = rm_anova(load_design(o->design));
    if (o->json)
      std::cout << anova_to_json(result).dump(2) << "\n";
    else
      std::cout << "Repeated-measures ANOVA, " << result.subjects << " subjects\n\n"
                << anova_text_table(result);
  });

  // ---- posthoc ----
  auto ph_opt = std::make_shared<PosthocOptions>();
  auto* ph =
      analyze->add_subcommand("posthoc", "Pairwise comparisons for a main effect or an interaction's cells");
  add_design_options(ph, ph_opt->design);
  ph->add_option("--effect", ph_opt->effect, "Effect: a factor (A) or an interaction (A:B)")->required();
  ph->add_option("--method", ph_opt->method, "tukey (pooled-error Tukey HSD) or bonferroni (paired t-tests)")
      ->check(CLI::IsMember({"tukey", "bonferroni"}))
      ->capture_default_str();
  ph->add_flag("--simple", ph_opt->simple,
               "Only compare cells that differ in one factor (simple comparisons)");
  ph->add_option("--max-comparisons", ph_opt->max_comparisons,
                 "Refuse (exit 2) a family with more pairwise comparisons than this, before any work")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  ph->add_flag("--json", ph_opt->json, "Print JSON");
  ph->callback([o = ph_opt] {
    const auto design = load_design(o->design);
    const auto factors = parse_effect(design, o->effect);
    const auto method = o->method == "tukey" ? PosthocMethod::tukey : PosthocMethod::bonferroni;
    const auto result = posthoc(design, factors, method, o->simple, o->max_comparisons);
    if (o->json) {
      auto j = posthoc_to_json(result);
      if (factors.size() > 1) {
        nlohmann::json simple = nlohmann::json::array();
        for (size_t at : factors)
          for (const auto& se : simple_effects(design, factors, at))
            simple.push_back({{"at", se.at},
                              {"effect", se.effect.name},
                              {"df1", se.effect.df1},
                              {"df2", se.effect.df2},
                              {"F", se.effect.f},
                              {"p", se.effect.p},
                              {"pes", se.effect.pes}});
        j["simple_effects"] = simple;
      }
      std::cout << j.dump(2) << "\n";
      return;
    }
    std::cout << "Post-hoc comparisons for " << result.effect << " ("
              << (method == PosthocMethod::tukey ? "Tukey HSD" : "paired t-tests, Bonferroni") << ")\n\n"
              << posthoc_markdown_table(result);
    if (factors.size() > 1) {
      std::cout << "\nSimple effects:\n";
      for (size_t at : factors)
        for (const auto& se : simple_effects(design, factors, at))
          std::cout << "  " << se.effect.name << " at " << se.at << ": " << apa_f_sentence(se.effect) << "\n";
    }
  });

  // ---- psychometric ----
  auto psy_opt = std::make_shared<PsychometricOptions>();
  PsychometricRequest& req = psy_opt->request;
  auto* psy = analyze->add_subcommand(
      "psychometric",
      "Logistic psychometric functions per subject (and condition) by maximum likelihood; thresholds "
      "(D_crit / V_crit at 0.5, the 5 % point), bootstrap CIs, group table and RM-ANOVA of thresholds");
  psy->add_option("--csv", psy_opt->csv, "Tidy CSV: one row per binary trial")->required();
  psy->add_option("--subject", req.subject, "Subject column")->required();
  psy->add_option("--x", req.x,
                  "Stimulus column (distance in metres, or volume in m^3 with --x-transform cbrt)")
      ->required();
  psy->add_option("--response", req.response, "Binary response column (0/1)")->required();
  psy->add_option("--by", req.by, "Condition column: one fit per subject and level");
  psy->add_option("--p", psy_opt->probabilities, "Threshold probabilities, comma-separated")
      ->capture_default_str();
  psy->add_option("--bootstrap", req.bootstrap, "Parametric-bootstrap replicates per fit (0 = none)")
      ->check(CLI::Range(0, 100000));
  psy->add_option("--seed", req.seed, "Bootstrap seed")->capture_default_str();
  psy->add_option("--x-transform", req.x_transform,
                  "none | cbrt (cube root of volume, seed 001 section 4.2.3)")
      ->check(CLI::IsMember({"none", "cbrt"}))
      ->capture_default_str();
  psy->add_option("--guess", req.options.guess,
                  "Fixed guess rate (lower asymptote); thresholds are then points of "
                  "the underlying logistic (see analysis/psychometric_fit.hpp)");
  psy->add_option("--lapse", req.options.lapse, "Fixed lapse rate (1 - upper asymptote)");
  psy->add_flag("--allow-simulated-mix", psy_opt->allow_simulated_mix, kAllowMixHelp);
  psy->add_flag("--json", psy_opt->json, "Print {\"fits\": [...], \"groups\": [...], \"anova\": ...}");
  psy->callback([o = psy_opt] {
    PsychometricRequest& pr = o->request;
    pr.probabilities.clear();
    for (const auto& s : split_list(o->probabilities)) {
      try {
        pr.probabilities.push_back(std::stod(s));
      } catch (const std::exception&) {
        throw InputError("--p: not a number: '" + s + "'");
      }
    }
    const auto result = analyze_psychometric(read_unmixed_csv(o->csv, o->allow_simulated_mix), pr);
    if (o->json) {
      std::cout << psychometric_to_json(result).dump(2) << "\n";
      return;
    }
    for (const auto& row : result.fits) {
      std::printf("%-10s %-12s intercept %9.4f slope %9.4f", row.subject.c_str(), row.by.c_str(),
                  row.fit.intercept, row.fit.slope);
      for (size_t k = 0; k < pr.probabilities.size(); ++k) {
        std::printf("  x(%s) %.4f", probability_key(pr.probabilities[k]).c_str(), row.thresholds[k]);
        if (!row.ci.empty()) std::printf(" [%.4f, %.4f]", row.ci[k].lower, row.ci[k].upper);
      }
      std::printf("%s\n", row.fit.warning.empty() ? "" : ("  WARNING: " + row.fit.warning).c_str());
    }
    std::cout << "\n" << psychometric_markdown_table(result, "");
  });

  // ---- report ----
  auto report_opt = std::make_shared<ReportOptions>();
  auto* report = analyze->add_subcommand(
      "report", "Markdown report with figures from a study's response CSVs (real or simulated)");
  report
      ->add_option("study_dir", report_opt->study_dir,
                   "Folder with the study's response CSVs (*.csv, tidy rows)")
      ->required();
  report->add_option("--spec", report_opt->spec_path, "The experiment spec (YAML) the study ran")->required();
  report->add_option("--out", report_opt->out_dir, "Output folder (report.md, figures/)")->required();
  report->add_flag("--allow-simulated-mix", report_opt->allow_simulated_mix, kAllowMixHelp);
  report->callback([o = report_opt] {
    check_study_dir_unmixed(o->study_dir, o->allow_simulated_mix);
    const auto path = write_study_report(o->study_dir, o->spec_path, o->out_dir);
    std::cout << "wrote " << path << "\n";
  });
});
}  // namespace
}  // namespace crowdlab::cli
