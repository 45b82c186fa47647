#include "framework/body/mpfb2_shape.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "framework/core/error.hpp"

namespace crowdlab {
namespace {

using Weights = std::vector<std::pair<std::string, double>>;

/// The named targets a macro variable selects at value x, with their weights (non-zero only).
Weights variable_weights(const Mpfb2Model& model, const std::string& variable, double x) {
  const auto it = model.macro_parts().find(variable);
  if (it == model.macro_parts().end()) throw InputError("macro.json has no variable '" + variable + "'");
  for (const MacroPart& part : it->second) {
    if (x < part.lowest || x > part.highest) continue;
    const double t = part.highest > part.lowest ? (x - part.lowest) / (part.highest - part.lowest) : 0.0;
    Weights out;
    if (!part.low.empty() && 1.0 - t > 0.0) out.emplace_back(part.low, 1.0 - t);
    if (!part.high.empty() && t > 0.0) out.emplace_back(part.high, t);
    return out;
  }
  throw InputError("macro variable '" + variable + "' = " + std::to_string(x) +
                   " is outside macro.json's parts");
}

void check_unit(double v, const char* name, double lo = 0.0) {
  if (!std::isfinite(v) || v < lo || v > 1.0)
    throw InputError(std::string("mpfb2 shape: ") + name + " must be in [" + std::to_string(lo) +
                     ", 1], got " + std::to_string(v));
}

}  // namespace

void validate_shape_params(const Mpfb2ShapeParams& p) {
  check_unit(p.gender, "gender");
  check_unit(p.age, "age (adult targets only)", 0.5);
  check_unit(p.muscle, "muscle");
  check_unit(p.weight, "weight");
  check_unit(p.height, "height");
  check_unit(p.proportions, "proportions");
  check_unit(p.african, "african");
  check_unit(p.asian, "asian");
  check_unit(p.caucasian, "caucasian");
  if (p.african + p.asian + p.caucasian <= 0.0) throw InputError("mpfb2 shape: race shares sum to 0");
}

std::vector<std::pair<std::string, double>> macro_target_weights(const Mpfb2Model& model,
                                                                 const Mpfb2ShapeParams& p) {
  validate_shape_params(p);
  const Weights g = variable_weights(model, "gender", p.gender);
  const Weights a = variable_weights(model, "age", p.age);
  const Weights m = variable_weights(model, "muscle", p.muscle);
  const Weights w = variable_weights(model, "weight", p.weight);
  const Weights h = variable_weights(model, "height", p.height);
  const Weights pr = variable_weights(model, "proportions", p.proportions);
  const double race_sum = p.african + p.asian + p.caucasian;
  const Weights race = {{"african", p.african / race_sum},
                        {"asian", p.asian / race_sum},
                        {"caucasian", p.caucasian / race_sum}};
  std::map<std::string, double> out;
  for (const auto& [gn, gw] : g) {
    for (const auto& [an, aw] : a) {
      for (const auto& [rn, rw] : race)
        if (rw > 0.0) out[rn + "-" + gn + "-" + an] += rw * gw * aw;
      for (const auto& [mn, mw] : m) {
        for (const auto& [wn, ww] : w) {
          const std::string stem = gn + "-" + an + "-" + mn + "-" + wn;
          const double base = gw * aw * mw * ww;
          out["universal-" + stem] += base;
          for (const auto& [hn, hw] : h) out["height/" + stem + "-" + hn] += base * hw;
          for (const auto& [pn, pw] : pr) out["proportions/" + stem + "-" + pn] += base * pw;
        }
      }
    }
  }
  std::vector<std::pair<std::string, double>> list;
  for (const auto& [name, weight] : out)
    if (weight > 0.0) list.emplace_back(name, weight);
  return list;
}

std::vector<Vec3> shaped_vertices_dm(const Mpfb2Model& model, const Mpfb2ShapeParams& p) {
  std::vector<Vec3> v = model.base().vertices;
  for (const auto& [name, weight] : macro_target_weights(model, p)) {
    const ShapeTarget& t = model.target(name);
    for (size_t k = 0; k < t.indices.size(); ++k)
      v[static_cast<size_t>(t.indices[k])] += weight * t.offsets_dm[k];
  }
  return v;
}

}  // namespace crowdlab
