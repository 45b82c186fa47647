// Conditions: the full crossing of factor levels x repetitions (and the practice crossing).
// Ids are made of factor names and level texts only ("density-2.22_viewpoint-V1_method-ours_rep-1"),
// and seeds are derive_seed(spec.seed, id), so neither depends on a level's position in its list.
#include "framework/core/seed.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "framework/spec/type_condition.hpp"

namespace crowdlab {
namespace {

// Appends one condition per combination of `factors` (first factor slowest) and repetition
// 1..repetitions (fastest). `fixed` holds levels of factors outside the crossing.
void cross(const ExperimentSpec& spec, const std::vector<const Factor*>& factors,
           const std::map<std::string, FactorLevel>& fixed, int repetitions, bool practice,
           std::vector<Condition>& out) {
  std::vector<size_t> index(factors.size(), 0);
  for (const Factor* f : factors)
    if (f->levels.empty()) return;
  while (true) {
    Condition base;
    base.levels = fixed;
    base.practice = practice;
    for (size_t i = 0; i < factors.size(); ++i) base.levels[factors[i]->name] = factors[i]->levels[index[i]];
    // Ids list factors in spec order, whichever of them were crossed or fixed.
    std::string stem = practice ? "practice_" : "";
    for (const Factor& f : spec.factors) {
      auto it = base.levels.find(f.name);
      if (it != base.levels.end()) stem += f.name + "-" + it->second.text + "_";
    }
    for (int r = 1; r <= repetitions; ++r) {
      Condition c = base;
      c.repetition = r;
      c.id = stem + "rep-" + std::to_string(r);
      c.seed = derive_seed(spec.seed, c.id);
      type_condition(spec, c);
      out.push_back(std::move(c));
    }
    // Odometer increment, last factor fastest.
    size_t k = factors.size();
    while (k > 0) {
      --k;
      if (++index[k] < factors[k]->levels.size()) break;
      index[k] = 0;
      if (k == 0) return;
    }
    if (factors.empty()) return;
  }
}

}  // namespace

std::vector<Condition> enumerate_conditions(const ExperimentSpec& spec) {
  std::vector<const Factor*> factors;
  for (const Factor& f : spec.factors) factors.push_back(&f);
  std::vector<Condition> out;
  cross(spec, factors, {}, spec.repetitions, false, out);
  return out;
}

std::vector<Condition> enumerate_practice_conditions(const ExperimentSpec& spec) {
  const ProtocolSpec& p = spec.protocol;
  if (p.practice_factors.empty()) return {};
  auto practice_factor = [&](const std::string& name) -> const Factor* {
    for (const Factor& f : p.practice_factors)
      if (f.name == name) return &f;
    return nullptr;
  };
  // Crossed: the practice factors and, when blocks are used and practice does not name the block
  // factor, the block factor (one practice set per block). Every other factor is held at its first level.
  std::vector<const Factor*> crossed;
  std::map<std::string, FactorLevel> fixed;
  for (const Factor& f : spec.factors) {
    if (const Factor* pf = practice_factor(f.name))
      crossed.push_back(pf);
    else if (!p.block_by.empty() && f.name == p.block_by)
      crossed.push_back(&f);
    else if (!f.levels.empty())
      fixed[f.name] = f.levels.front();
  }
  std::vector<Condition> out;
  cross(spec, crossed, fixed, 1, true, out);
  return out;
}

}  // namespace crowdlab
