#include "study_ui/estimate_power.hpp"

#include <algorithm>
#include <map>

#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "study_ui/paired_t_test.hpp"
#include "study_ui/study_question.hpp"

namespace crowdlab::study {
namespace {

/// Indices (into questions) of the items the dv averages.
std::vector<size_t> dv_items(const ProtocolSpec& protocol, const std::vector<StudyQuestion>& questions,
                             std::string& dv) {
  if (dv.empty()) dv = protocol.composites.empty() ? questions.front().id : protocol.composites.front().id;
  auto index_of = [&](const std::string& id) {
    for (size_t i = 0; i < questions.size(); ++i)
      if (questions[i].id == id) return i;
    throw InputError(SourceLocation{"", 0, 0, "--dv"}, "unknown question '" + id + "'");
  };
  for (const CompositeSpec& c : protocol.composites)
    if (c.id == dv) {
      std::vector<size_t> items;
      for (const auto& item : c.items) items.push_back(index_of(item));
      if (items.empty())
        throw InputError(SourceLocation{"", 0, 0, "--dv"}, "composite '" + dv + "' has no items");
      return items;
    }
  for (size_t i = 0; i < questions.size(); ++i)
    if (questions[i].id == dv) return {i};
  throw InputError(SourceLocation{"", 0, 0, "--dv"}, "'" + dv + "' is neither a question nor a composite id");
}

}  // namespace

std::vector<PowerRow> estimate_power(const ExperimentSpec& spec, const StimulusManifest& manifest,
                                     const ObserverModel& model, const PowerOptions& opt) {
  const std::vector<StudyQuestion> questions = resolve_questions(spec.protocol);
  std::string dv = opt.dv;
  const std::vector<size_t> items = dv_items(spec.protocol, questions, dv);
  if (opt.simulations < 1) throw InputError(SourceLocation{"", 0, 0, "--simulations"}, "must be >= 1");
  if (!(opt.alpha > 0 && opt.alpha < 1))
    throw InputError(SourceLocation{"", 0, 0, "--alpha"}, "must be in (0, 1)");
  std::vector<const StimulusEntry*> at_a, at_b;
  for (const StimulusEntry& e : manifest.entries) {
    if (e.practice) continue;
    auto it = e.factors.find(opt.factor);
    if (it == e.factors.end()) break;
    if (it->second == opt.level_a) at_a.push_back(&e);
    if (it->second == opt.level_b) at_b.push_back(&e);
  }
  if (std::find(manifest.factor_names.begin(), manifest.factor_names.end(), opt.factor) ==
      manifest.factor_names.end())
    throw InputError(SourceLocation{"", 0, 0, "--contrast"},
                     "factor '" + opt.factor + "' is not in the manifest");
  if (at_a.empty() || at_b.empty())
    throw InputError(SourceLocation{"", 0, 0, "--contrast"},
                     "no test stimuli at " + opt.factor + "=" + (at_a.empty() ? opt.level_a : opt.level_b));

  auto mean_dv = [&](const Observer& o, const std::vector<const StimulusEntry*>& entries, Rng& rng) {
    double sum = 0.0;
    for (const StimulusEntry* e : entries) {
      const std::vector<Answer> answers = simulate_answers(model, o, *e, questions, rng);
      double item_sum = 0.0;
      for (size_t i : items) item_sum += reverse_coded(questions[i], answers[i].raw);
      sum += item_sum / static_cast<double>(items.size());
    }
    return sum / static_cast<double>(entries.size());
  };

  std::vector<PowerRow> rows;
  for (int n : opt.sample_sizes) {
    if (n < 2) throw InputError(SourceLocation{"", 0, 0, "--n"}, "sample sizes must be >= 2");
    // Counted in simulated observers, not studies: one study of --n 1000000000 takes hours (issue 33).
    Progress progress("power n=" + std::to_string(n),
                      static_cast<size_t>(opt.simulations) * static_cast<size_t>(n));
    PowerRow row;
    row.n = n;
    row.simulations = opt.simulations;
    int significant = 0;
    for (int s = 0; s < opt.simulations; ++s) {
      std::vector<double> diffs;
      for (int i = 0; i < n; ++i) {
        const std::uint64_t seed = derive_seed(
            opt.seed, "power:n" + std::to_string(n) + ":s" + std::to_string(s) + ":o" + std::to_string(i));
        const Observer o = draw_observer(model, seed);
        Rng rng(derive_seed(seed, "answers"));
        const double a = mean_dv(o, at_a, rng);
        const double b = mean_dv(o, at_b, rng);
        diffs.push_back(b - a);
        progress.advance();
      }
      const PairedTTest t = paired_t_test(diffs);
      if (t.p_two_sided < opt.alpha) ++significant;
      row.mean_difference += t.mean_difference;
      row.mean_cohens_dz += std::isfinite(t.cohens_dz) ? t.cohens_dz : 0.0;
    }
    row.power = static_cast<double>(significant) / opt.simulations;
    row.mean_difference /= opt.simulations;
    row.mean_cohens_dz /= opt.simulations;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace crowdlab::study
