#include "analysis/reliability.hpp"

#include <cmath>
#include <limits>

#include "framework/core/error.hpp"

namespace crowdlab::analysis {

PairReliability pair_reliability(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw InputError("pair_reliability: the two items have different lengths");
  if (a.size() < 2) throw InputError("pair_reliability: need at least 2 answer pairs");
  const double n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= n;
  mb /= n;
  double vaa = 0, vbb = 0, vab = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    vaa += (a[i] - ma) * (a[i] - ma);
    vbb += (b[i] - mb) * (b[i] - mb);
    vab += (a[i] - ma) * (b[i] - mb);
  }
  PairReliability r;
  r.n = a.size();
  r.pearson_r = (vaa > 0 && vbb > 0) ? vab / std::sqrt(vaa * vbb) : std::numeric_limits<double>::quiet_NaN();
  const double total = vaa + vbb + 2.0 * vab;
  r.cronbach_alpha = total > 0 ? 2.0 * (1.0 - (vaa + vbb) / total) : std::numeric_limits<double>::quiet_NaN();
  return r;
}

}  // namespace crowdlab::analysis
