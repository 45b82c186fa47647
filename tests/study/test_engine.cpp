// Study engine: questions and reverse coding, trial lists (practice, blocks, Latin square), the
// paired t-test, simulated observers and power.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "framework/core/error.hpp"
#include "study_ui/build_trial_list.hpp"
#include "study_ui/estimate_power.hpp"
#include "study_ui/paired_t_test.hpp"
#include "study_ui/simulated_observer.hpp"
#include "study_ui/study_question.hpp"
#include "tests/study/study_fixture.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_engine {

using namespace crowdlab;
using namespace crowdlab::study;

TEST_CASE("default questions follow the papers' protocols", "[study]") {
  ProtocolSpec p;
  p.type = ProtocolType::likert;
  const auto likert = resolve_questions(p);
  REQUIRE(likert.size() == 6);
  for (size_t i = 0; i < 6; ++i) {
    CHECK(likert[i].points == 6);
    CHECK(likert[i].reverse == (i % 2 == 1));  // Q2, Q4, Q6 are the negative items (seed 000 §4.4.1)
  }
  CHECK(likert[0].low_label == "I strongly disagree");
  CHECK(likert[0].high_label == "I fully agree");
  p.type = ProtocolType::two_afc;
  const auto afc = resolve_questions(p);
  REQUIRE(afc.size() == 2);
  CHECK(afc[0].kind == QuestionKind::yesno);
  CHECK(afc[0].text == "Did the characters go through each other?");
  CHECK(afc[1].points == 7);
  p.type = ProtocolType::rating;
  const auto rating = resolve_questions(p);
  REQUIRE(rating.size() == 2);
  CHECK(rating[0].points == 7);
  CHECK(rating[1].points == 7);
}

TEST_CASE("reverse coding is (k+1) - Q for reverse-keyed items only, and an involution", "[study]") {
  for (int k = 2; k <= 11; ++k) {
    StudyQuestion q;
    q.points = k;
    for (int raw = 1; raw <= k; ++raw) {
      q.reverse = false;
      CHECK(reverse_coded(q, raw) == raw);
      q.reverse = true;
      CHECK(reverse_coded(q, raw) == k + 1 - raw);
      CHECK(reverse_coded(q, reverse_coded(q, raw)) == raw);
    }
  }
  StudyQuestion six;
  six.points = 6;
  six.reverse = true;
  CHECK(reverse_coded(six, 2) == 5);  // seed 000 §4.4.3: 7 - Q
}

TEST_CASE("spec questions are validated", "[study]") {
  ProtocolSpec p;
  p.questions = {{"A", "a", false, "scale", 0, {}}, {"A", "b", false, "scale", 0, {}}};
  CHECK_THROWS_AS(resolve_questions(p), InputError);
  p.questions = {{"A", "a", false, "scale", 12, {}}};
  CHECK_THROWS_AS(resolve_questions(p), InputError);
  p.questions = {{"A", "a", true, "yesno", 0, {}}};
  CHECK_THROWS_AS(resolve_questions(p), InputError);
  p.questions = {{"A", "a", false, "scale", 5, {"never", "often"}}};
  const auto q = resolve_questions(p);
  CHECK(q[0].points == 5);
  CHECK(q[0].low_label == "never");
}

namespace {
StimulusManifest synthetic_manifest(int per_block, const std::vector<std::string>& blocks,
                                    int practice_per_block, int global_practice) {
  StimulusManifest m;
  m.factor_names = {"scenario", "density"};
  for (const auto& b : blocks)
    for (int i = 0; i < per_block; ++i) {
      StimulusEntry e;
      e.id = b + "_" + std::to_string(i);
      e.factors = {{"scenario", b}, {"density", std::to_string(i)}};
      m.entries.push_back(e);
    }
  for (const auto& b : blocks)
    for (int i = 0; i < practice_per_block; ++i) {
      StimulusEntry e;
      e.id = "practice_" + b + "_" + std::to_string(i);
      e.factors = {{"scenario", b}, {"density", "0"}};
      e.practice = true;
      m.entries.push_back(e);
    }
  for (int i = 0; i < global_practice; ++i) {
    StimulusEntry e;
    e.id = "practice_global_" + std::to_string(i);
    e.factors = {{"scenario", ""}, {"density", "0"}};
    e.practice = true;
    m.entries.push_back(e);
  }
  return m;
}
}  // namespace

TEST_CASE("trial lists: every stimulus once, practice first, blocks contiguous, per-participant order",
          "[study]") {
  const std::vector<std::string> blocks = {"A", "B"};
  const StimulusManifest m = synthetic_manifest(12, blocks, 3, 2);
  ProtocolSpec p;
  p.block_by = "scenario";
  std::set<std::vector<std::string>> orders;
  std::map<std::string, int> first_block_count;
  for (int participant = 1; participant <= 40; ++participant) {
    const std::string id = "P" + std::to_string(participant);
    const auto trials = build_trial_list(p, m, 7, id);
    REQUIRE(trials.size() == m.entries.size());
    std::multiset<std::string> ids;
    std::vector<std::string> order;
    for (size_t i = 0; i < trials.size(); ++i) {
      CHECK(trials[i].index == static_cast<int>(i) + 1);
      ids.insert(trials[i].stimulus.id);
      order.push_back(trials[i].stimulus.id);
    }
    for (const auto& e : m.entries) CHECK(ids.count(e.id) == 1);
    // The 2 global practice trials first; then each block starts with its own 3 practice trials.
    CHECK(trials[0].practice);
    CHECK(trials[1].practice);
    CHECK(trials[0].stimulus.id.rfind("practice_global_", 0) == 0);
    for (size_t start : {size_t{2}, size_t{2 + 15}}) {
      for (size_t k = 0; k < 3; ++k) CHECK(trials[start + k].practice);
      for (size_t k = 3; k < 15; ++k) {
        CHECK_FALSE(trials[start + k].practice);
        CHECK(trials[start + k].block == trials[start].block);
        CHECK(trials[start + k].stimulus.factors.at("scenario") == trials[start].block);
      }
    }
    ++first_block_count[trials[2].block];
    CHECK(build_trial_list(p, m, 7, id)[20].stimulus.id == trials[20].stimulus.id);  // deterministic
    orders.insert(order);
  }
  CHECK(orders.size() == 40);          // every participant a different order
  CHECK(first_block_count["A"] >= 8);  // random block order: both blocks first, often
  CHECK(first_block_count["B"] >= 8);
}

TEST_CASE("Latin-square block order: Williams rows are permutations and balance positions and carry-over",
          "[study]") {
  for (int n : {2, 3, 4, 5, 6, 8}) {
    std::vector<std::vector<int>> position_count(static_cast<size_t>(n),
                                                 std::vector<int>(static_cast<size_t>(n), 0));
    std::map<std::pair<int, int>, int> adjacent;
    for (int r = 0; r < n; ++r) {
      const auto row = williams_row(n, static_cast<std::uint64_t>(r));
      std::vector<int> sorted = row;
      std::sort(sorted.begin(), sorted.end());
      for (int i = 0; i < n; ++i) CHECK(sorted[static_cast<size_t>(i)] == i);
      for (int i = 0; i < n; ++i)
        ++position_count[static_cast<size_t>(row[static_cast<size_t>(i)])][static_cast<size_t>(i)];
      for (int i = 0; i + 1 < n; ++i)
        ++adjacent[{row[static_cast<size_t>(i)], row[static_cast<size_t>(i) + 1]}];
    }
    for (const auto& counts : position_count)
      for (int c : counts) CHECK(c == 1);  // each block once in each position over n participants
    if (n % 2 == 0)
      for (const auto& [pair, c] : adjacent) CHECK(c == 1);  // first-order carry-over balanced (even n)
  }
  CHECK(participant_number("P07") == 7);
  CHECK(participant_number("S012") == 12);
  const StimulusManifest m = synthetic_manifest(3, {"A", "B", "C", "D"}, 0, 0);
  ProtocolSpec p;
  p.block_by = "scenario";
  p.block_order = BlockOrder::latin_square;
  const auto t1 = build_trial_list(p, m, 1, "P01");
  const auto t2 = build_trial_list(p, m, 1, "P02");
  const std::vector<std::string> names = {"A", "B", "C", "D"};
  for (int k = 0; k < 4; ++k) {
    CHECK(t1[static_cast<size_t>(3 * k)].block ==
          names[static_cast<size_t>(williams_row(4, 1)[static_cast<size_t>(k)])]);
    CHECK(t2[static_cast<size_t>(3 * k)].block ==
          names[static_cast<size_t>(williams_row(4, 2)[static_cast<size_t>(k)])]);
  }
  p.block_by = "nope";
  CHECK_THROWS_AS(build_trial_list(p, m, 1, "P01"), InputError);
}

TEST_CASE("paired t-test matches the closed form", "[study]") {
  const PairedTTest t = paired_t_test({1, 2, 3, 4, 5});
  CHECK(t.mean_difference == Approx(3.0));
  CHECK(t.t == Approx(3.0 / std::sqrt(2.5 / 5.0)).epsilon(1e-12));
  CHECK(t.df == 4.0);
  // df = 4: P(T > t) = 1/2 - t (6 + t^2) / (2 (4 + t^2)^{3/2}) (closed form of the t CDF for 4 df).
  const double x = t.t;
  const double upper = 0.5 - x * (6.0 + x * x) / (2.0 * std::pow(4.0 + x * x, 1.5));
  CHECK(t.p_two_sided == Approx(2.0 * upper).epsilon(1e-10));
  CHECK(t.p_two_sided == Approx(0.0132356).epsilon(1e-5));
  CHECK(paired_t_test({1, -1, 1, -1}).p_two_sided == Approx(1.0));
  CHECK_THROWS_AS(paired_t_test({1.0}), InputError);
}

TEST_CASE("simulated observers: psychometric curves fall with distance and rise with volume", "[study]") {
  const ObserverModel model;
  StimulusEntry s;
  for (const std::string shoulder : {"0", "1", "2"}) {
    s.factors = {{"shoulder", shoulder}, {"distance", "0.2"}};
    const Observer o = draw_observer(model, 5);
    double previous = 2.0;
    for (double d = 0.2; d <= 0.7001; d += 0.05) {
      s.factors["distance"] = std::to_string(d);
      const double p = collision_probability(o, s);
      CHECK(p < previous);
      previous = p;
    }
    // At the observer's own threshold the probability is 1/2.
    s.factors["distance"] = std::to_string(o.d_crit_m.at(shoulder));
    CHECK(collision_probability(o, s) == Approx(0.5).margin(1e-5));
  }
  // Population threshold means come out near seed 001 Table 1.
  double mean0 = 0, mean2 = 0;
  for (int i = 0; i < 400; ++i) {
    const Observer o = draw_observer(model, static_cast<std::uint64_t>(i));
    mean0 += o.d_crit_m.at("0") / 400;
    mean2 += o.d_crit_m.at("2") / 400;
  }
  CHECK(mean0 == Approx(0.52).margin(0.01));
  CHECK(mean2 == Approx(0.27).margin(0.01));
  StimulusEntry v;
  v.factors = {{"shoulder", "0"}};
  const Observer o = draw_observer(model, 3);
  double previous = -1.0;
  for (double vol = 0.0; vol < 0.1; vol += 0.01) {
    v.v_i_m = vol;
    const double p = collision_probability(o, v);
    CHECK(p > previous);
    previous = p;
  }
}

TEST_CASE("simulated answers: valid, deterministic, 'ours' rated higher, more overlap rated lower",
          "[study]") {
  ObserverModel model;
  ProtocolSpec p;
  const auto questions = resolve_questions(p);
  StimulusEntry base, ours;
  base.factors = {{"method", "baseline"}};
  ours.factors = {{"method", "ours"}};
  base.mean_overlap_l = 1.5;
  ours.mean_overlap_l = 0.05;
  double sum_base = 0, sum_ours = 0;
  for (int i = 0; i < 200; ++i) {
    const Observer o = draw_observer(model, static_cast<std::uint64_t>(i));
    Rng rng(static_cast<std::uint64_t>(i)), rng2(static_cast<std::uint64_t>(i));
    const auto a = simulate_answers(model, o, base, questions, rng);
    const auto a2 = simulate_answers(model, o, base, questions, rng2);
    const auto b = simulate_answers(model, o, ours, questions, rng);
    for (size_t q = 0; q < questions.size(); ++q) {
      CHECK(questions[q].valid(a[q].raw));
      CHECK(a[q].raw == a2[q].raw);
      CHECK((q == 0 || a[q].rt_ms > a[q - 1].rt_ms));
      sum_base += reverse_coded(questions[q], a[q].raw);
      sum_ours += reverse_coded(questions[q], b[q].raw);
    }
  }
  CHECK(sum_ours > sum_base + 200 * 6 * 0.5);
  CHECK_THROWS_AS(model.set("nonsense=1"), InputError);
  CHECK_THROWS_AS(model.set("lapse=2"), InputError);
  model.set("effect.method.ours=1.5");
  CHECK(model.level_effects.at("method=ours") == 1.5);
}

TEST_CASE("power by simulation grows with n and effect, and is about alpha with no effect", "[study]") {
  const auto dir = test::scratch_dir("study-power");
  StimulusManifest m;
  m.factor_names = {"density", "method"};
  for (const std::string d : {"1", "2", "3"})
    for (const std::string meth : {"baseline", "ours"}) {
      StimulusEntry e;
      e.id = d + meth;
      e.factors = {{"density", d}, {"method", meth}};
      m.entries.push_back(e);
    }
  ExperimentSpec spec = test::likert_spec();
  PowerOptions opt;
  opt.factor = "method";
  opt.level_a = "baseline";
  opt.level_b = "ours";
  opt.sample_sizes = {4, 16};
  opt.simulations = test::kSanitized ? 40 : 150;
  ObserverModel model;
  model.level_effects = {{"method=ours", 0.4}};
  const auto rows = estimate_power(spec, m, model, opt);
  REQUIRE(rows.size() == 2);
  CHECK(rows[1].power > rows[0].power);
  CHECK(rows[1].mean_difference > 0.1);
  model.level_effects = {{"method=ours", 0.0}};
  opt.sample_sizes = {10};
  const auto null_rows = estimate_power(spec, m, model, opt);
  CHECK(null_rows[0].power < 0.15);
  opt.factor = "viewpoint";
  CHECK_THROWS_AS(estimate_power(spec, m, model, opt), InputError);
}

TEST_CASE("simulated ratings: collision frequency rises and naturalness falls with overlap", "[study]") {
  ObserverModel model;
  ProtocolSpec p;
  p.type = ProtocolType::rating;
  p.questions = {
      {"collisions", "How often did you see collisions between characters?", false, "scale", 7, {}},
      {"naturalness", "How natural was the way the characters moved in the crowd?", false, "scale", 7, {}}};
  const auto questions = resolve_questions(p);
  StimulusEntry sparse, dense;
  sparse.mean_overlap_l = 0.01;
  dense.mean_overlap_l = 2.0;
  double collisions[2] = {0, 0}, natural[2] = {0, 0};
  for (int i = 0; i < 300; ++i) {
    const Observer o = draw_observer(model, static_cast<std::uint64_t>(i));
    Rng rng(static_cast<std::uint64_t>(i) + 1000);
    int k = 0;
    for (const StimulusEntry* s : {&sparse, &dense}) {
      const auto a = simulate_answers(model, o, *s, questions, rng);
      collisions[k] += a[0].raw;
      natural[k] += a[1].raw;
      ++k;
    }
  }
  CHECK(collisions[1] > collisions[0] + 300 * 0.5);
  CHECK(natural[1] < natural[0] - 300 * 0.5);
}

}  // namespace test_engine
