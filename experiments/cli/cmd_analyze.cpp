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
#include "analysis/clmm_fit.hpp"
#include "analysis/lmm_fit.hpp"
#include "analysis/posthoc.hpp"
#include "analysis/psychometric_table.hpp"
#include "analysis/rm_anova.hpp"
#include "analysis/simulated_rows.hpp"
#include "analysis/study_report.hpp"
#include "experiments/cli/command_table.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "framework/core/error.hpp"
#include "framework/core/library_error.hpp"
#include "framework/spec/work_limits.hpp"

namespace crowdlab::cli::cmd_analyze {
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
  std::string csv, dv, subject, within, between;
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

void add_design_options(
    Command* cmd, DesignArgs& a, bool with_between = false,
    const std::string& between_help =
        "Between-subject factor columns, comma-separated (e.g. group); groups may differ in "
        "size (Type III sums of squares, as afex)") {
  cmd->add_option("--csv", a.csv, "Tidy CSV: one row per trial (repetitions are averaged per cell)")
      ->required();
  cmd->add_option("--dv", a.dv, "Dependent-variable column (numeric)")->required();
  cmd->add_option("--subject", a.subject, "Subject (participant) column")->required();
  auto* within =
      cmd->add_option("--within", a.within, "Within-subject factor columns, comma-separated (e.g. A,B,C)");
  if (with_between)
    cmd->add_option("--between", a.between, between_help);
  else
    within->required();
  cmd->add_option(
         "--max-levels", a.limits.max_levels,
         "Refuse (exit 2) a factor with more levels than this, before any work (see docs/analysis.md)")
      ->check(check::positive_number())
      ->capture_default_str();
  cmd->add_option("--max-cells", a.limits.max_cells,
                  "Refuse (exit 2) a design with more cells (product of the levels) than this")
      ->check(check::positive_number())
      ->capture_default_str();
  cmd->add_flag("--allow-simulated-mix", a.allow_simulated_mix, kAllowMixHelp);
}

struct AnovaOptions {
  DesignArgs design;
  bool json = false;
};

struct PosthocOptions {
  DesignArgs design;
  std::string effect, method = "tukey", error = "classic";
  bool json = false, simple = false;
  size_t max_comparisons = kDefaultMaxComparisons;
};

struct PsychometricOptions {
  PsychometricRequest request;
  std::string csv, probabilities = "0.5,0.05", lapse = "fixed";
  bool json = false, allow_simulated_mix = false;
};

struct LmmOptions {
  std::string csv, formula;
  bool ml = false, reml = false, json = false, allow_simulated_mix = false;
  LmmLimits limits;
};

void print_lmm(const LmmResult& r) {
  std::printf("Linear mixed model (%s), %zu observations\n\nFixed effects:\n", r.reml ? "REML" : "ML",
              r.observations);
  for (const auto& f : r.fixed)
    std::printf("  %-28s %12.6f  SE %10.6f  t %9.3f  df %9.2f  p %.4g\n", f.term.c_str(), f.estimate, f.se,
                f.t, f.df, f.p);
  std::printf("\nRandom effects:\n");
  for (const auto& s : r.random_sd)
    std::printf("  %-14s %-20s SD %.6f\n", s.group.c_str(), s.term.c_str(), s.sd);
  for (const auto& c : r.random_corr)
    std::printf("  %-14s corr(%s, %s) %.4f\n", c.group.c_str(), c.term1.c_str(), c.term2.c_str(), c.corr);
  std::printf("  residual SD %.6f\n\n%s %.6f%s\n", r.residual_sd, r.reml ? "REML criterion" : "deviance",
              r.criterion, r.converged ? "" : " (NOT converged)");
  for (const auto& w : r.warnings) std::printf("WARNING: %s\n", w.c_str());
}

struct ClmmOptions {
  std::string csv, formula, link = "logit";
  bool json = false, allow_simulated_mix = false;
};

void print_clmm(const ClmmResult& r) {
  std::printf("Cumulative link mixed model (%s link, Laplace), %zu observations\n\nThresholds:\n",
              r.link.c_str(), r.observations);
  for (const auto& t : r.thresholds)
    std::printf("  %-12s %10.5f  SE %8.5f\n", t.name.c_str(), t.estimate, t.se);
  std::printf("\nFixed effects:\n");
  for (const auto& f : r.fixed)
    std::printf("  %-28s %10.5f  SE %8.5f  z %8.3f  p %.4g\n", f.name.c_str(), f.estimate, f.se, f.z, f.p);
  std::printf("\n");
  for (const auto& g : r.random)
    std::printf("Random intercept SD (%s, %zu levels): %.5f\n", g.group.c_str(), g.levels, g.sd);
  std::printf("log-likelihood %.6f%s\n", r.loglik, r.converged ? "" : " (NOT converged)");
  for (const auto& w : r.warnings) std::printf("WARNING: %s\n", w.c_str());
}

struct ReportOptions {
  std::string study_dir, spec_path, out_dir;
  bool allow_simulated_mix = false;
  double max_participant_items = kMaxReportParticipantItems;  // framework/spec/work_limits.hpp
};

WithinDesign load_design(const DesignArgs& a) {
  const auto within = split_list(a.within);
  const auto between = split_list(a.between);
  if (within.empty() && between.empty()) throw InputError("--within/--between: no factor given");
  return build_within_design(read_unmixed_csv(a.csv, a.allow_simulated_mix), a.dv, a.subject, within,
                             a.limits, between);
}

}  // namespace

void add_analyze_command(Command& root) {
  auto* analyze =
      root.add_subcommand("analyze", "Statistics: RM-ANOVA, post-hoc tests, psychometric fits, reports");
  analyze->require_subcommand(1);

  // ---- anova ----
  auto anova_opt = std::make_shared<AnovaOptions>();
  auto* anova = analyze->add_subcommand(
      "anova",
      "Repeated-measures, mixed (split-plot) or between-subjects ANOVA (Type III with between factors, as "
      "afex) with Mauchly's test, Greenhouse-Geisser and Huynh-Feldt corrections, partial and generalised "
      "eta squared");
  add_design_options(anova, anova_opt->design, true);
  anova->add_flag(
      "--json", anova_opt->json,
      "Print {\"effects\": [{\"effect\", \"df1\", \"df2\", \"F\", \"p\", \"pes\", \"ges\", \"mauchly_W\", "
      "\"mauchly_p\", \"gg_eps\", \"hf_eps\", \"p_gg\", \"p_hf\", ...}]} (null where not applicable)");
  anova->callback([o = anova_opt] {
    at_input_boundary(o->design.csv, [&] {
      const auto design = load_design(o->design);
      const auto result = rm_anova(design);
      const char* kind = design.between.empty()   ? "Repeated-measures ANOVA"
                         : design.factors.empty() ? "Between-subjects ANOVA (Type III)"
                                                  : "Mixed ANOVA (Type III)";
      if (o->json)
        std::cout << anova_to_json(result).dump(2) << "\n";
      else
        std::cout << kind << ", " << result.subjects << " subjects\n\n" << anova_text_table(result);
    });
  });

  // ---- posthoc ----
  auto ph_opt = std::make_shared<PosthocOptions>();
  auto* ph =
      analyze->add_subcommand("posthoc", "Pairwise comparisons for a main effect or an interaction's cells");
  add_design_options(ph, ph_opt->design, true,
                     "Between-subject factor columns, comma-separated (e.g. group): --effect may then name "
                     "them too (G, A:G), compared as emmeans compares an afex model's cells; needs --error "
                     "pooled or separate");
  ph->add_option("--effect", ph_opt->effect, "Effect: a factor (A) or an interaction (A:B)")->required();
  ph->add_option("--method", ph_opt->method, "tukey (pooled-error Tukey HSD) or bonferroni (paired t-tests)")
      ->check(check::is_member({"tukey", "bonferroni"}))
      ->capture_default_str();
  ph->add_option(
        "--error", ph_opt->error,
        "classic (Tukey with the effect's own error term, or paired t), pooled (emmeans' univariate "
        "model: error strata pooled, Satterthwaite df) or separate (emmeans' multivariate model: each "
        "contrast's own error); with pooled/separate the statistic is t and --method adjusts p")
      ->check(check::is_member({"classic", "pooled", "separate"}))
      ->capture_default_str();
  ph->add_flag("--simple", ph_opt->simple,
               "Only compare cells that differ in one factor (simple comparisons)");
  ph->add_option("--max-comparisons", ph_opt->max_comparisons,
                 "Refuse (exit 2) a family with more pairwise comparisons than this, before any work")
      ->check(check::positive_number())
      ->capture_default_str();
  ph->add_flag("--json", ph_opt->json, "Print JSON");
  ph->callback([o = ph_opt] {
    at_input_boundary(o->design.csv, [&] {
      const auto design = load_design(o->design);
      const auto method = o->method == "tukey" ? PosthocMethod::tukey : PosthocMethod::bonferroni;
      const auto error = o->error == "pooled"     ? PosthocError::pooled
                         : o->error == "separate" ? PosthocError::separate
                                                  : PosthocError::classic;
      // "(emmeans' univariate model, Tukey-adjusted p)" for --error pooled|separate.
      const std::string model = std::string("emmeans' ") +
                                (error == PosthocError::pooled ? "univariate" : "multivariate") + " model, " +
                                (method == PosthocMethod::tukey ? "Tukey" : "Bonferroni") + "-adjusted p";
      if (!design.between.empty()) {
        const auto result = posthoc_mixed(design, parse_mixed_effect(design, o->effect), method, o->simple,
                                          o->max_comparisons, error);
        if (o->json)
          std::cout << posthoc_to_json(result).dump(2) << "\n";
        else
          std::cout << "Post-hoc comparisons for " << result.effect << " (" << model << ")\n\n"
                    << posthoc_markdown_table(result);
        return;
      }
      if (split_list(o->design.within).empty()) throw InputError("--within: no within-subject factor given");
      const auto factors = parse_effect(design, o->effect);
      const auto result = posthoc(design, factors, method, o->simple, o->max_comparisons, error);
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
                << (error != PosthocError::classic   ? model
                    : method == PosthocMethod::tukey ? "Tukey HSD"
                                                     : "paired t-tests, Bonferroni")
                << ")\n\n"
                << posthoc_markdown_table(result);
      if (factors.size() > 1) {
        std::cout << "\nSimple effects:\n";
        for (size_t at : factors)
          for (const auto& se : simple_effects(design, factors, at))
            std::cout << "  " << se.effect.name << " at " << se.at << ": " << apa_f_sentence(se.effect)
                      << "\n";
      }
    });
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
      ->check(check::range(0, 100000));
  psy->add_option("--seed", req.seed, "Bootstrap seed")->capture_default_str();
  psy->add_option("--x-transform", req.x_transform,
                  "none | cbrt (cube root of volume, seed 001 section 4.2.3)")
      ->check(check::is_member({"none", "cbrt"}))
      ->capture_default_str();
  psy->add_option("--guess", req.options.guess,
                  "Fixed guess rate (lower asymptote); thresholds are then points of "
                  "the underlying logistic (see analysis/psychometric_fit.hpp)");
  psy->add_option("--lapse", psy_opt->lapse,
                  "fixed (at --lapse-rate), symmetric (fit guess = lapse = lambda in [0, 0.5) by maximum "
                  "likelihood, per subject and condition; see analysis/psychometric_lapse.hpp), or a "
                  "number: the fixed lapse rate")
      ->capture_default_str();
  psy->add_option("--lapse-rate", req.options.lapse,
                  "Fixed lapse rate (1 - upper asymptote) for --lapse fixed")
      ->capture_default_str();
  psy->add_flag("--allow-simulated-mix", psy_opt->allow_simulated_mix, kAllowMixHelp);
  psy->add_flag("--json", psy_opt->json, "Print {\"fits\": [...], \"groups\": [...], \"anova\": ...}");
  psy->callback([o = psy_opt] {
    at_input_boundary(o->csv, [&] {
      PsychometricRequest& pr = o->request;
      if (o->lapse == "symmetric") {
        pr.options.fit_symmetric_lapse = true;
      } else if (o->lapse != "fixed") {
        try {
          size_t used = 0;
          pr.options.lapse = std::stod(o->lapse, &used);
          // "nan" parses, and was then reported as a CSV problem of the first subject (issue 33).
          if (used != o->lapse.size() || !(pr.options.lapse >= 0.0 && pr.options.lapse < 1.0))
            throw InputError("");
        } catch (const std::exception&) {
          throw InputError("--lapse: expected fixed, symmetric or a number in [0, 1), got '" + o->lapse +
                           "'");
        }
      }
      pr.probabilities.clear();
      for (const auto& s : split_list(o->probabilities)) {
        // The whole text, in (0, 1): stod read "0.5abc" as 0.5, silently (issue 33).
        try {
          size_t used = 0;
          const double p = std::stod(s, &used);
          if (used != s.size() || !(p > 0.0 && p < 1.0)) throw InputError("");
          pr.probabilities.push_back(p);
        } catch (const std::exception&) {
          throw InputError("--p: expected probabilities in (0, 1), comma-separated, got '" + s + "'");
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
        if (row.fit.lapse_fitted)
          std::printf(" lapse %.4f%s", row.fit.lapse, row.fit.lapse_at_boundary ? " (bound)" : "");
        std::printf(" nll %.4f dev %.2f/%d%s", row.fit.nll, row.goodness.deviance, row.goodness.df,
                    row.goodness.overdispersed ? " OVERDISPERSED" : "");
        for (size_t k = 0; k < pr.probabilities.size(); ++k) {
          std::printf("  x(%s) %.4f", probability_key(pr.probabilities[k]).c_str(), row.thresholds[k]);
          if (!row.ci.empty()) std::printf(" [%.4f, %.4f]", row.ci[k].lower, row.ci[k].upper);
        }
        std::printf("%s\n", row.fit.warning.empty() ? "" : ("  WARNING: " + row.fit.warning).c_str());
      }
      std::cout << "\n" << psychometric_markdown_table(result, "");
    });
  });

  // ---- lmm ----
  auto lmm_opt = std::make_shared<LmmOptions>();
  auto* lmm = analyze->add_subcommand(
      "lmm",
      "Linear mixed model as lme4::lmer: correlated random intercepts and slopes, crossed groups "
      "(profiled deviance, sparse Cholesky, BOBYQA; see analysis/lmm_fit.hpp)");
  lmm->add_option("--csv", lmm_opt->csv, "Tidy CSV: one row per observation")->required();
  lmm->add_option("--formula", lmm_opt->formula,
                  "lme4 formula, e.g. \"Y ~ a * b + (1 + b | S)\"; text columns are factors (treatment "
                  "coding, levels sorted, the first the reference)")
      ->required();
  auto* reml_flag = lmm->add_flag("--reml", lmm_opt->reml, "Restricted maximum likelihood (the default)");
  lmm->add_flag("--ml", lmm_opt->ml, "Maximum likelihood (for likelihood-ratio tests of fixed effects)")
      ->excludes(reml_flag);
  lmm->add_flag("--json", lmm_opt->json,
                "Print {\"fixed\": [{term, estimate, se, t, df, p}] (Satterthwaite df, as lmerTest), "
                "\"random\": [{group, term, sd} | {group, "
                "term1, term2, corr}], \"residual_sd\", \"reml_criterion\" | \"deviance\", \"converged\", "
                "\"singular\", \"warnings\", \"observations\"}");
  lmm->add_flag("--allow-simulated-mix", lmm_opt->allow_simulated_mix, kAllowMixHelp);
  lmm->add_option("--max-covariance-parameters", lmm_opt->limits.max_covariance_parameters,
                  "Refuse (exit 2), before the fit, random terms with more covariance parameters than this "
                  "(q (q + 1) / 2 for q effects per level; the fit's work grows with their square)")
      ->check(check::range(1, 100000))
      ->capture_default_str();
  lmm->callback([o = lmm_opt] {
    at_input_boundary(o->csv, [&] {
      const auto result =
          fit_lmm(read_unmixed_csv(o->csv, o->allow_simulated_mix), o->formula, !o->ml, o->limits);
      if (o->json)
        std::cout << lmm_to_json(result).dump(2) << "\n";
      else
        print_lmm(result);
    });
  });

  // ---- clmm ----
  auto clmm_opt = std::make_shared<ClmmOptions>();
  auto* clmm = analyze->add_subcommand(
      "clmm",
      "Cumulative link mixed model for ordinal (Likert) answers as ordinal::clmm: flexible thresholds, "
      "random intercepts (one grouping factor or crossed ones), Laplace approximation (see "
      "analysis/clmm_fit.hpp)");
  clmm->add_option("--csv", clmm_opt->csv, "Tidy CSV: one row per answer")->required();
  clmm->add_option(
          "--formula", clmm_opt->formula,
          "e.g. \"R ~ a * b + (1 | S)\" or \"R ~ a + (1 | S) + (1 | stimulus)\": random-intercept terms")
      ->required();
  clmm->add_option("--link", clmm_opt->link, "logit or probit")
      ->check(check::is_member({"logit", "probit"}))
      ->capture_default_str();
  clmm->add_flag("--json", clmm_opt->json,
                 "Print {\"thresholds\": [{name, estimate, se}], \"fixed\": [{term, estimate, se, z, p}], "
                 "\"random\": [{group, sd}], \"loglik\", \"link\", \"converged\", \"observations\", "
                 "\"warnings\"}");
  clmm->add_flag("--allow-simulated-mix", clmm_opt->allow_simulated_mix, kAllowMixHelp);
  clmm->callback([o = clmm_opt] {
    at_input_boundary(o->csv, [&] {
      const auto result = fit_clmm(read_unmixed_csv(o->csv, o->allow_simulated_mix), o->formula, o->link);
      if (o->json)
        std::cout << clmm_to_json(result).dump(2) << "\n";
      else
        print_clmm(result);
    });
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
  report
      ->add_option("--max-participant-items", report_opt->max_participant_items,
                   "Refuse (exit 2), before any model is fitted, studies with more participants x Likert "
                   "items than this (one mixed model per item, a random intercept per participant; about "
                   "0.01 s each)")
      ->check(check::range(1.0, 1e9))
      ->capture_default_str();
  report->callback([o = report_opt] {
    at_input_boundary(o->study_dir, [&] {
      const OutputFolderLock lock(o->out_dir);  // one process per folder (output_folder_lock.hpp)
      check_study_dir_unmixed(o->study_dir, o->allow_simulated_mix);
      const auto path = write_study_report(o->study_dir, o->spec_path, o->out_dir, o->max_participant_items);
      std::cout << "wrote " << path << "\n";
    });
  });
}

}  // namespace crowdlab::cli::cmd_analyze
