#include "analysis/study_report.hpp"

#include <algorithm>
#include <boost/math/policies/error_handling.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "analysis/analysis_json.hpp"
#include "analysis/apa_format.hpp"
#include "analysis/clmm_fit.hpp"
#include "analysis/kolmogorov_smirnov.hpp"
#include "analysis/model_not_fitted.hpp"
#include "analysis/plot_interaction.hpp"
#include "analysis/plot_psychometric.hpp"
#include "analysis/posthoc.hpp"
#include "analysis/psychometric_table.hpp"
#include "analysis/reliability.hpp"
#include "analysis/study_responses.hpp"
#include "framework/core/error.hpp"
#include "framework/core/printable_excerpt.hpp"
#include "framework/core/write_file.hpp"
#include "framework/spec/estimate_work.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::analysis {
namespace {
namespace fs = std::filesystem;

std::string fmt(double v, int decimals = 2) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string safe_name(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s;
}

// Axis labels with units for the factors of the seed papers' specs (seed 000 section 4.4.2: density in
// characters per m²; seed 001: distance in metres, trigger in percent); other factors are categorical.
std::string factor_axis_label(const std::string& factor) {
  if (factor == "density") return "density (characters/m#u2#d)";
  if (factor == "distance") return "distance (m)";
  if (factor == "trigger") return "trigger (% of characters)";
  if (factor == "shoulder") return "shoulder (characters with shoulder motion)";
  return factor + " (level)";
}

struct Context {
  ExperimentSpec spec;
  StudyResponses responses;
  std::vector<std::string> factors;  ///< spec factors with >= 2 levels in the data, spec order
  fs::path out;
  std::string md;
};

// Fits one model of the report. A model the data cannot support (singular, separated, non-finite, not
// converged; issue 32) throws InputError/ModelNotFitted or a numeric error of Boost.Math or the standard
// library; its reason is returned and the report goes on. Anything else (I/O, memory) still ends the run.
template <class Fit>
std::optional<std::string> try_fit(Fit&& fit) {
  try {
    fit();
    return std::nullopt;
  } catch (const InputError& e) {
    return std::string(e.what());
  } catch (const boost::math::evaluation_error& e) {
    return std::string(e.what());
  } catch (const std::domain_error& e) {
    return std::string(e.what());
  } catch (const std::overflow_error& e) {
    return std::string(e.what());
  } catch (const std::underflow_error& e) {
    return std::string(e.what());
  }
}

// Every file of the report goes through the framework's atomic writer: a link, device or FIFO under the
// report's name is refused rather than written through (issue 32), and a full disk is named.
void write_report_file(const fs::path& path, const std::string& text) {
  write_file_atomic(path, text, /*durable=*/false);
}

std::string not_fitted_line(const std::string& why) {
  return "Not fitted: " + why + "\n\n";
}

// participant, <factors...>, value rows of one measure (a question or a composite).
CsvTable measure_table(const Context& ctx, const std::vector<std::string>& items, const std::string& name) {
  const CsvTable& t = ctx.responses.table;
  const size_t q_col = t.column("question"), v_col = t.column("value"), p_col = t.column("participant"),
               s_col = t.column("stimulus");
  std::vector<size_t> f_cols;
  for (const auto& f : ctx.factors) f_cols.push_back(t.column(f));
  // (participant, stimulus) -> item values, in order of first appearance.
  std::map<std::pair<std::string, std::string>, size_t> index;
  std::vector<std::pair<size_t, std::map<std::string, double>>> trials;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const auto& q = t.cell(r, q_col);
    if (std::find(items.begin(), items.end(), q) == items.end()) continue;
    auto [it, inserted] = index.emplace(std::make_pair(t.cell(r, p_col), t.cell(r, s_col)), trials.size());
    if (inserted) trials.push_back({r, {}});
    trials[it->second].second[q] = t.number(r, v_col);  // std::stod threw a bare "stod" (issue 33)
  }
  CsvTable out;
  out.source = ctx.responses.files.size() == 1 ? ctx.responses.files[0] : "responses of " + name;
  out.header = {"participant"};
  out.header.insert(out.header.end(), ctx.factors.begin(), ctx.factors.end());
  out.header.push_back("value");
  for (const auto& [first_row, values] : trials) {
    double sum = 0;
    for (const auto& item : items) {
      const auto v = values.find(item);
      if (v == values.end())
        throw InputError(ctx.responses.sources[first_row] + ":" + std::to_string(t.line_numbers[first_row]) +
                         ": participant '" + t.cell(first_row, p_col) + "', stimulus '" +
                         t.cell(first_row, s_col) + "': no answer to '" + item + "' (needed by " + name +
                         ")");
      sum += v->second;
    }
    // 1.7e308 answers overflow the sum: name the row here, where the real file is known, not the
    // composite's derived table ("responses of Q_CR:8:5: not a finite number: ''", issue 33).
    if (!std::isfinite(sum))
      throw InputError(SourceLocation{ctx.responses.sources[first_row], t.line_numbers[first_row],
                                      static_cast<int>(v_col) + 1, "column 'value'"},
                       "participant " + quote_value(t.cell(first_row, p_col)) + ", stimulus " +
                           quote_value(t.cell(first_row, s_col)) + ": the items of " + name +
                           " add up past the largest double (values too large to average)");
    std::vector<std::string> row = {t.cell(first_row, p_col)};
    for (size_t c : f_cols) row.push_back(t.cell(first_row, c));
    row.push_back(csv_number(sum / static_cast<double>(items.size())));
    out.rows.push_back(row);
    out.line_numbers.push_back(t.line_numbers[first_row]);
  }
  return out;
}

void reliability_section(Context& ctx, const CompositeSpec& comp) {
  if (comp.items.size() != 2) return;
  const CsvTable a = measure_table(ctx, {comp.items[0]}, comp.items[0]);
  const CsvTable b = measure_table(ctx, {comp.items[1]}, comp.items[1]);
  if (a.rows.size() != b.rows.size() || a.rows.empty()) return;
  std::vector<double> va, vb;
  for (size_t r = 0; r < a.rows.size(); ++r) {
    va.push_back(a.number(r, a.header.size() - 1));
    vb.push_back(b.number(r, b.header.size() - 1));
  }
  const auto rel = pair_reliability(va, vb);
  ctx.md += "Internal reliability of " + comp.items[0] + " and " + comp.items[1] + " (reverse-coded), over " +
            std::to_string(rel.n) + " trials: ";
  if (std::isfinite(rel.pearson_r) && std::isfinite(rel.cronbach_alpha))
    ctx.md += "r = " + fmt(rel.pearson_r) + ", Cronbach's α = " + fmt(rel.cronbach_alpha) + ".\n\n";
  else
    ctx.md += "not defined (an item's answers, or their sum, do not vary).\n\n";
}

void interaction_plots(Context& ctx, const WithinDesign& design, const std::string& name,
                       const std::string& y_label) {
  const size_t k = design.factors.size();
  const size_t series_factor = k - 1;
  for (size_t f = 0; f < (k == 1 ? 1 : k - 1); ++f) {
    std::vector<size_t> effect = k == 1 ? std::vector<size_t>{0} : std::vector<size_t>{f, series_factor};
    const Eigen::MatrixXd m = effect_subject_means(design, effect);
    InteractionPlot plot;
    plot.title =
        name + (k == 1 ? "" : ": " + design.factors[f].name + " × " + design.factors[series_factor].name);
    plot.x_label = factor_axis_label(design.factors[f].name);
    plot.y_label = y_label;
    plot.x_levels = design.factors[f].levels;
    plot.note = "mean ± 1 SD over participants";
    const size_t ns = k == 1 ? 1 : design.factors[series_factor].levels.size();
    for (size_t s = 0; s < ns; ++s) {
      InteractionSeries series;
      series.label = k == 1 ? name : design.factors[series_factor].levels[s];
      for (size_t x = 0; x < plot.x_levels.size(); ++x) {
        const Eigen::VectorXd col = m.col(static_cast<Eigen::Index>(k == 1 ? x : x * ns + s));
        series.mean.push_back(col.mean());
        series.error.push_back(std::sqrt((col.array() - col.mean()).square().sum() / (col.size() - 1.0)));
      }
      plot.series.push_back(series);
    }
    if (k > 1) {
      std::vector<SimpleEffect> simple;
      // A simple effect without error variance has no test: its stars are left out.
      if (!try_fit([&] { simple = simple_effects(design, effect, f); }))
        for (const auto& se : simple)
          plot.stars.push_back(significance_stars(
              se.effect.p_gg && se.effect.mauchly_p && *se.effect.mauchly_p < 0.05 ? *se.effect.p_gg
                                                                                   : se.effect.p));
    }
    const std::string stem = "interaction_" + safe_name(name) + "_" + safe_name(design.factors[f].name);
    plot_interaction(plot, (ctx.out / "figures" / stem).string());
    ctx.md += "![" + plot.title + "](figures/" + stem + ".png)\n\n";
  }
  if (k > 1)
    ctx.md += "Stars: simple effect of " + design.factors[series_factor].name +
              " at each x level (* p < .05, ** p < .01, *** p < .001).\n\n";
}

// The ordinal model beside the ANOVA (issue 20; Liddell & Kruschke 2018, J. Exp. Soc. Psychol. 79): a
// cumulative link mixed model (logit link, clmm's default) of one Likert item's answers per trial
// (reverse-coded, as the ANOVA's), the varying spec factors crossed as categorical fixed effects and a
// random intercept per participant: R's clmm(factor(value) ~ f1 * f2 + (1 | participant)). A model
// that cannot be fitted (fewer than 3 answer levels used, a missing factor combination) is reported as
// such; the rest of the report stands.
void clmm_section(Context& ctx, const std::string& item, nlohmann::json& stats) {
  const CsvTable t = measure_table(ctx, {item}, item);
  std::string formula = "value ~ ";
  for (size_t f = 0; f < ctx.factors.size(); ++f) formula += (f ? " * " : "") + ctx.factors[f];
  formula += " + (1 | participant)";
  ctx.md += "Ordinal model of " + item +
            " (cumulative link mixed model, logit link, Laplace approximation, as R's `ordinal::clmm`; `" +
            formula + "`, factors categorical; estimates in log cumulative odds of a higher answer):\n\n";
  ClmmResult fit;
  const auto why = try_fit([&] {
    fit = fit_clmm(t, formula, "logit", {ctx.factors.begin(), ctx.factors.end()});
  });
  nlohmann::json j = why ? nlohmann::json{{"not_fitted", *why}} : clmm_to_json(fit);
  j["item"] = item;
  j["formula"] = formula;
  stats["clmm"].push_back(j);
  if (why) {
    ctx.md += not_fitted_line(*why);
    return;
  }
  ctx.md += clmm_markdown_table(fit) + "\n";
  for (const auto& w : fit.warnings) ctx.md += "Warning: " + w + ".\n\n";
}

// The residual normality line of an ANOVA (subject x cell interaction residuals), with its Q-Q data.
void normality_section(Context& ctx, const WithinDesign& design, const std::string& name) {
  const Eigen::MatrixXd& y = design.cell_means;
  const Eigen::VectorXd rm = y.rowwise().mean(), cm = y.colwise().mean().transpose();
  std::vector<double> residuals;
  for (Eigen::Index i = 0; i < y.rows(); ++i)
    for (Eigen::Index c = 0; c < y.cols(); ++c) residuals.push_back(y(i, c) - rm[i] - cm[c] + y.mean());
  NormalityCheck normal;
  if (const auto why = try_fit([&] { normal = normality_check(residuals); })) {
    ctx.md += "Normality of residuals: not tested: " + *why + "\n\n";
    return;
  }
  std::ostringstream qq;
  qq << "theoretical,sample\n";
  for (size_t i = 0; i < normal.sample.size(); ++i)
    qq << normal.theoretical[i] << "," << normal.sample[i] << "\n";
  write_report_file(ctx.out / "stats" / ("qq_" + safe_name(name) + ".csv"), qq.str());
  ctx.md += "Normality of residuals: Kolmogorov-Smirnov D = " + fmt(normal.ks.statistic, 3) +
            ", p = " + apa_p(normal.ks.p) + " (Q-Q data: stats/qq_" + safe_name(name) + ".csv).\n\n";
}

// Tukey post-hocs of every significant ANOVA effect; one that cannot be computed is "Not fitted".
void posthoc_section(Context& ctx, const WithinDesign& design, const RmAnovaResult& anova,
                     const std::string& name, nlohmann::json& stats) {
  for (const auto& e : anova.effects) {
    const double p = (e.mauchly_p && *e.mauchly_p < 0.05) ? *e.p_gg : e.p;
    if (p >= 0.05) continue;
    ctx.md += "Post-hoc (Tukey HSD" + std::string(e.factors.size() > 1 ? ", simple comparisons" : "") +
              ") for " + e.name + ":\n\n";
    PosthocResult ph;
    if (const auto why =
            try_fit([&] { ph = posthoc(design, e.factors, PosthocMethod::tukey, e.factors.size() > 1); })) {
      stats["posthoc"].push_back({{"effect", e.name}, {"not_fitted", *why}});
      ctx.md += not_fitted_line(*why);
      continue;
    }
    stats["posthoc"].push_back(posthoc_to_json(ph));
    if (ph.pairs.size() <= 30)
      ctx.md += posthoc_markdown_table(ph) + "\n";
    else
      ctx.md += std::to_string(ph.pairs.size()) + " comparisons: see stats/" + safe_name(name) + ".json.\n\n";
  }
}

void describe_cell_means(Context& ctx, const WithinDesign& design) {
  ctx.md += "Mean ± SD over participants:";
  for (size_t f = 0; f < design.factors.size(); ++f) {
    const Eigen::MatrixXd m = effect_subject_means(design, {f});
    ctx.md += (f ? ";" : "") + std::string(" ") + design.factors[f].name + " ";
    for (Eigen::Index l = 0; l < m.cols(); ++l) {
      const Eigen::VectorXd c = m.col(l);
      const double sd = std::sqrt((c.array() - c.mean()).square().sum() / (c.size() - 1.0));
      ctx.md += (l ? ", " : "") + design.factors[f].levels[static_cast<size_t>(l)] + ": " + fmt(c.mean()) +
                " ± " + fmt(sd);
    }
  }
  ctx.md += ".\n\n";
}

// One rating measure: its ANOVA, residual normality, one CLMM per item, post-hocs and plots. Each model
// that the data cannot support is written "Not fitted: <why>" (issue 32) and the others still are.
void measure_section(Context& ctx, const std::string& name, const std::vector<std::string>& items) {
  ctx.md += "### " + name + "\n\n";
  if (items.size() > 1)
    ctx.md += "Composite of " + std::to_string(items.size()) + " items, averaged per trial.\n\n";
  nlohmann::json stats = {
      {"measure", name}, {"posthoc", nlohmann::json::array()}, {"clmm", nlohmann::json::array()}};
  const CsvTable t = measure_table(ctx, items, name);
  WithinDesign design;
  RmAnovaResult anova;
  const auto design_why =
      try_fit([&] { design = build_within_design(t, "value", "participant", ctx.factors); });
  const auto anova_why = design_why ? design_why : try_fit([&] { anova = rm_anova(design); });
  if (!design_why) describe_cell_means(ctx, design);
  if (anova_why) {
    stats["anova"] = {{"not_fitted", *anova_why}};
    ctx.md += "Repeated-measures ANOVA: " + not_fitted_line(*anova_why);
  } else {
    stats["anova"] = anova_to_json(anova);
    ctx.md += anova_markdown_table(anova) + "\n";
    for (const auto& e : anova.effects) ctx.md += "- " + e.name + ": " + apa_f_sentence(e) + "\n";
    ctx.md += "\n";
    normality_section(ctx, design, name);
  }
  for (const auto& item : items) clmm_section(ctx, item, stats);
  if (!anova_why) posthoc_section(ctx, design, anova, name, stats);
  write_report_file(ctx.out / "stats" / (safe_name(name) + ".json"), stats.dump(2) + "\n");
  if (design_why) return;
  const int points = ctx.spec.protocol.scale_points;
  interaction_plots(ctx, design, name, "Answer (1-" + std::to_string(points) + " scale)");
}

bool numeric_factor(const ExperimentSpec& spec, const std::string& name) {
  const Factor* f = spec.factor(name);
  if (!f || f->levels.size() < 3) return false;
  return std::all_of(f->levels.begin(), f->levels.end(), [](const auto& l) { return l.number.has_value(); });
}

void psychometric_section(Context& ctx, const QuestionSpec& q) {
  std::string x_factor;
  if (std::find(ctx.factors.begin(), ctx.factors.end(), "distance") != ctx.factors.end())
    x_factor = "distance";
  for (const auto& f : ctx.factors)
    if (x_factor.empty() && numeric_factor(ctx.spec, f)) x_factor = f;
  ctx.md += "### " + q.id + " (yes/no): psychometric functions\n\n";
  if (x_factor.empty()) {
    ctx.md += "No numeric factor with at least 3 levels: no psychometric fit.\n\n";
    return;
  }
  const CsvTable m = measure_table(ctx, {q.id}, q.id);
  CsvTable t;
  t.source = m.source;
  t.header = {"participant", "x", "response", "condition"};
  const size_t x_col = m.column(x_factor);
  for (size_t r = 0; r < m.rows.size(); ++r) {
    std::string cond;
    for (const auto& f : ctx.factors)
      if (f != x_factor) cond += (cond.empty() ? "" : ", ") + f + " " + m.cell(r, m.column(f));
    t.rows.push_back({m.cell(r, 0), m.cell(r, x_col), m.rows[r].back(), cond.empty() ? "all" : cond});
    t.line_numbers.push_back(m.line_numbers[r]);
  }
  PsychometricRequest req;
  req.subject = "participant";
  req.x = "x";
  req.response = "response";
  req.by = "condition";
  req.probabilities = {0.5, 0.05};
  req.bootstrap = 0;
  PsychometricAnalysis a;
  if (const auto why = try_fit([&] { a = analyze_psychometric(t, req); })) {
    write_report_file(ctx.out / "stats" / ("psychometric_" + safe_name(q.id) + ".json"),
                      nlohmann::json{{"not_fitted", *why}}.dump(2));
    ctx.md += not_fitted_line(*why);
    return;
  }
  ctx.md +=
      "Logistic fits of P(yes) against " + x_factor + " per participant and condition (maximum likelihood; " +
      "Firth's estimate where answers were completely separated).\n\nTable 1: thresholds (mean ± SD over "
      "participants).\n\n" +
      psychometric_markdown_table(a, x_factor == "distance" ? "m" : "") + "\n";
  size_t separated = 0;
  for (const auto& f : a.fits) separated += f.fit.separated;
  if (separated)
    ctx.md += std::to_string(separated) + " fit(s) had completely separated answers (Firth estimate).\n\n";
  write_report_file(ctx.out / "stats" / ("psychometric_" + safe_name(q.id) + ".json"),
                    psychometric_to_json(a).dump(2));
  PsychometricPlot plot;
  plot.title = q.id + ": psychometric functions";
  plot.x_label = factor_axis_label(x_factor);
  plot.y_label = "P(" + q.id + " = yes)";
  for (const auto& g : a.groups) {
    PsychometricCurve c;
    c.label = g.by;
    std::map<double, std::vector<double>> props;  // x -> per-participant proportion
    std::vector<double> px, py;
    for (const auto& row : a.fits) {
      if (row.by != g.by) continue;
      std::map<double, std::pair<double, double>> counts;
      for (size_t i = 0; i < row.x.size(); ++i) {
        counts[row.x[i]].first += row.y[i];
        counts[row.x[i]].second += 1;
        px.push_back(row.x[i]);
        py.push_back(row.y[i]);
      }
      for (const auto& [x, c2] : counts) props[x].push_back(c2.first / c2.second);
    }
    for (const auto& [x, v] : props) {
      double mean = 0, ss = 0;
      for (double p : v) mean += p;
      mean /= static_cast<double>(v.size());
      for (double p : v) ss += (p - mean) * (p - mean);
      c.x.push_back(x);
      c.proportion.push_back(mean);
      c.se.push_back(v.size() > 1 ? std::sqrt(ss / (v.size() - 1.0) / static_cast<double>(v.size())) : 0.0);
    }
    // A condition whose pooled answers cannot be fitted is drawn as points without a curve.
    PsychometricFit pooled;
    c.fitted = !try_fit([&] { pooled = fit_psychometric(px, py); }) && std::isfinite(pooled.threshold(0.5));
    c.intercept = pooled.intercept;
    c.slope = pooled.slope;
    c.threshold50 = c.fitted ? pooled.threshold(0.5) : std::numeric_limits<double>::quiet_NaN();
    plot.curves.push_back(c);
  }
  const std::string stem = "psychometric_" + safe_name(q.id);
  plot_psychometric(plot, (ctx.out / "figures" / stem).string());
  ctx.md += "![" + plot.title + "](figures/" + stem +
            ".png)\n\nPoints: mean proportion over participants (±1 SE); "
            "curves: logistic fit to the pooled answers of each condition; dashed: its 50 % point.\n\n";
}
// One cumulative link mixed model per Likert item: the composites' items and the scale questions in none.
double likert_items_fitted(const ExperimentSpec& spec) {
  std::set<std::string> in_composite;
  double items = 0;
  for (const auto& comp : spec.protocol.composites) {
    in_composite.insert(comp.items.begin(), comp.items.end());
    items += static_cast<double>(comp.items.size());
  }
  for (const auto& q : spec.protocol.questions)
    if (q.kind != "yesno" && !in_composite.count(q.id)) items += 1;
  return items;
}

}  // namespace

std::string write_study_report(const std::string& study_dir, const std::string& spec_path,
                               const std::string& out_dir, double max_participant_items) {
  Context ctx;
  ctx.spec = load_experiment_spec(spec_path);
  ctx.responses = read_study_responses(study_dir, ctx.spec);
  ctx.out = out_dir;
  const CsvTable& t = ctx.responses.table;
  std::set<std::string> participants;
  for (const auto& row : t.rows) participants.insert(row[t.column("participant")]);
  if (const auto problem =
          report_limit_problem(static_cast<double>(participants.size()), likert_items_fitted(ctx.spec),
                               max_participant_items, "--max-participant-items"))
    throw InputError(study_dir + ": " + *problem);
  fs::create_directories(ctx.out / "figures");
  fs::create_directories(ctx.out / "stats");
  for (const auto& f : ctx.responses.factors) {
    std::set<std::string> levels;
    const size_t c = t.column(f);
    for (const auto& row : t.rows) levels.insert(row[c]);
    if (levels.size() >= 2) ctx.factors.push_back(f);
  }
  if (ctx.factors.empty()) throw InputError(study_dir + ": no spec factor varies in the responses");
  ctx.md = "# " + ctx.spec.name + ": study report\n\n" +
           (ctx.spec.description.empty() ? "" : ctx.spec.description + "\n\n");
  ctx.md += "- Spec: `" + spec_path + "` (sha256 " + ctx.spec.source_hash.substr(0, 12) + ")\n";
  ctx.md += "- Responses: " + std::to_string(ctx.responses.files.size()) + " file(s) in `" + study_dir +
            "`, " + std::to_string(participants.size()) + " participants, " + std::to_string(t.rows.size()) +
            " answers (practice excluded)\n";
  std::string fl;
  for (const auto& f : ctx.factors) fl += (fl.empty() ? "" : ", ") + f;
  ctx.md += "- Within-subject factors: " + fl + "\n";
  ctx.md +=
      "- Method: repeated-measures ANOVA on per-participant cell means (repetitions averaged); α = .05; "
      "Mauchly's test, Greenhouse-Geisser correction where sphericity is violated; Tukey HSD post-hocs. "
      "Beside it, each Likert item's answers as ordinal data: a cumulative link mixed model (logit, "
      "random intercept per participant; Liddell & Kruschke 2018). Results are mean ± SD.\n\n";
  std::set<std::string> in_composite;
  ctx.md += "## Rating measures\n\n";
  for (const auto& comp : ctx.spec.protocol.composites) {
    in_composite.insert(comp.items.begin(), comp.items.end());
    ctx.md += "### " + comp.id + " reliability\n\n";
    reliability_section(ctx, comp);
    measure_section(ctx, comp.id, comp.items);
  }
  for (const auto& q : ctx.spec.protocol.questions)
    if (q.kind != "yesno" && !in_composite.count(q.id)) measure_section(ctx, q.id, {q.id});
  bool any_yesno = false;
  for (const auto& q : ctx.spec.protocol.questions)
    if (q.kind == "yesno") {
      if (!any_yesno) ctx.md += "## Detection measures\n\n";
      any_yesno = true;
      psychometric_section(ctx, q);
    }
  const fs::path path = ctx.out / "report.md";
  write_report_file(path, ctx.md);
  return path.string();
}

}  // namespace crowdlab::analysis
