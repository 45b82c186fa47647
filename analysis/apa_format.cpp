#include "analysis/apa_format.hpp"

#include <cmath>
#include <cstdio>

namespace crowdlab::analysis {
namespace {
std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "NA";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}
// Effect sizes and p without the leading zero.
std::string no_lead(double v, int decimals) {
  std::string s = fixed(v, decimals);
  if (s.rfind("0.", 0) == 0) return s.substr(1);
  if (s.rfind("-0.", 0) == 0) return "-" + s.substr(2);
  return s;
}
bool sphericity_violated(const RmAnovaEffect& e) {
  return e.mauchly_p.has_value() && *e.mauchly_p < 0.05;
}
}  // namespace

std::string apa_p(double p) {
  if (!std::isfinite(p)) return "NA";
  if (p < 0.001) return "< .001";
  return no_lead(p, 3);
}

std::string apa_f_sentence(const RmAnovaEffect& e) {
  const bool gg = sphericity_violated(e) && e.gg_eps.has_value();
  const double eps = gg ? *e.gg_eps : 1.0;
  const double p = gg ? *e.p_gg : e.p;
  const int df_dec = gg ? 2 : 0;
  std::string s =
      "F(" + fixed(e.df1 * eps, df_dec) + ", " + fixed(e.df2 * eps, df_dec) + ") = " + fixed(e.f, 2);
  s += ", p " + (p < 0.001 ? std::string("< .001") : "= " + apa_p(p));
  s += ", η²p = " + no_lead(e.pes, 2) + ", η²G = " + no_lead(e.ges, 2);
  if (gg) s += " (Greenhouse-Geisser, ε = " + no_lead(eps, 2) + ")";
  return s;
}

std::string anova_markdown_table(const RmAnovaResult& result) {
  std::string s =
      "| Effect | df | F | p | η²p | η²G | Mauchly W (p) | ε GG | ε HF | |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& e : result.effects) {
    const bool gg = sphericity_violated(e);
    const double eps = gg ? *e.gg_eps : 1.0;
    const double p = gg ? *e.p_gg : e.p;
    s += "| " + e.name + " | " + fixed(e.df1 * eps, gg ? 2 : 0) + ", " + fixed(e.df2 * eps, gg ? 2 : 0) +
         (gg ? " (GG)" : "") + " | " + fixed(e.f, 2) + " | " + apa_p(p) + " | " + no_lead(e.pes, 2) + " | " +
         no_lead(e.ges, 2) + " | ";
    s += e.mauchly_w ? no_lead(*e.mauchly_w, 3) + " (" + apa_p(*e.mauchly_p) + ")" : "–";
    s += " | " + (e.gg_eps ? no_lead(*e.gg_eps, 3) : "–") + " | " + (e.hf_eps ? fixed(*e.hf_eps, 3) : "–") +
         " | " + significance_stars(p) + " |\n";
  }
  return s;
}

std::string anova_text_table(const RmAnovaResult& result) {
  char buf[512];
  std::string s;
  std::snprintf(buf, sizeof buf, "%-22s %5s %7s %10s %10s %8s %6s %6s %16s %7s %7s %10s %10s\n", "Effect",
                "df1", "df2", "F", "p", "", "pes", "ges", "Mauchly W (p)", "GG eps", "HF eps", "p[GG]",
                "p[HF]");
  s += buf;
  for (const auto& e : result.effects) {
    const std::string mauchly =
        e.mauchly_w ? fixed(*e.mauchly_w, 3) + " (" + fixed(*e.mauchly_p, 3) + ")" : "-";
    std::snprintf(buf, sizeof buf, "%-22s %5.0f %7.0f %10.3f %10.4g %8s %6.3f %6.3f %16s %7s %7s %10s %10s\n",
                  e.name.c_str(), e.df1, e.df2, e.f, e.p, significance_stars(e.p).c_str(), e.pes, e.ges,
                  mauchly.c_str(), e.gg_eps ? fixed(*e.gg_eps, 3).c_str() : "-",
                  e.hf_eps ? fixed(*e.hf_eps, 3).c_str() : "-", e.p_gg ? apa_p(*e.p_gg).c_str() : "-",
                  e.p_hf ? apa_p(*e.p_hf).c_str() : "-");
    s += buf;
  }
  s += "\nAPA: \n";
  for (const auto& e : result.effects) s += "  " + e.name + ": " + apa_f_sentence(e) + "\n";
  return s;
}

std::string posthoc_markdown_table(const PosthocResult& result) {
  const bool tukey = result.method == PosthocMethod::tukey;
  // Classic Tukey reports q; the other tests (and emmeans' models, --error pooled|separate) report t.
  const bool q = tukey && result.error == PosthocError::classic;
  std::string s = std::string("| Comparison | Mean A | Mean B | Difference | SE | df | ") + (q ? "q" : "t") +
                  " | p" + (tukey ? " (Tukey)" : " (Bonferroni)") +
                  " | |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& p : result.pairs)
    s += "| " + p.level_a + " vs " + p.level_b + " | " + fixed(p.mean_a, 2) + " | " + fixed(p.mean_b, 2) +
         " | " + fixed(p.difference, 2) + " | " + fixed(p.se, 3) + " | " +
         fixed(p.df, p.df == std::round(p.df) ? 0 : 2) + " | " + fixed(p.statistic, 2) + " | " +
         apa_p(p.p_adjusted) + " | " + significance_stars(p.p_adjusted) + " |\n";
  return s;
}

std::string clmm_markdown_table(const ClmmResult& result) {
  std::string s =
      "| Term | Estimate | SE | z | p | |\n"
      "|---|---|---|---|---|---|\n";
  for (const auto& f : result.fixed)
    s += "| " + f.name + " | " + fixed(f.estimate, 2) + " | " + fixed(f.se, 2) + " | " + fixed(f.z, 2) +
         " | " + apa_p(f.p) + " | " + significance_stars(f.p) + " |\n";
  std::string sds, counts;
  for (const auto& r : result.random) {
    sds += (sds.empty() ? "" : ", ") + r.group + " " + fixed(r.sd, 2);
    counts += ", " + std::to_string(r.levels) + " " + r.group + "s";
  }
  if (result.random.size() == 1)
    sds = "Random intercept SD (" + result.random[0].group + ") = " + fixed(result.random[0].sd, 2);
  else
    sds = "Random intercept SDs: " + sds;
  s += "\n" + sds + ", log-likelihood = " + fixed(result.loglik, 2) + ", " +
       std::to_string(result.observations) + " answers" + counts +
       (result.converged ? "" : " (the optimiser did NOT converge)") + ".\n";
  return s;
}

}  // namespace crowdlab::analysis
