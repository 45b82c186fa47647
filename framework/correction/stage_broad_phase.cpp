// Broad phase, on the world capsules at the predicted state (see corrector_step.hpp) (seed 000 §3.4: "for
// each body, we build an AABB after each simulation time step ... for inter-body collisions, we first test
// body-level AABBs to cull body pairs"). Body AABBs are swept along x (sort and sweep, Baraff 1992), which is
// O(N log N + pairs).
#include <algorithm>

#include <tbb/parallel_for.h>

#include "framework/correction/corrector_step.hpp"

namespace crowdlab {

void stage_broad_phase(const CorrectorModel& model, CorrectorState& state) {
  const int n = model.characters();
  const double reach = detection_reach(model.params);
  tbb::parallel_for(0, n, [&](int c) {
    const CorrectorBody& body = model.bodies[static_cast<size_t>(c)];
    Aabb box;
    for (size_t j = 0; j < kJointCount; ++j) {
      const size_t g = static_cast<size_t>(c) * kJointCount + j;
      const Quat& r = state.pred_rotation[g];
      const Vec3 origin = state.pred_com_m[g] - r * body.com_local_m[j];
      const Capsule& local = body.shape.capsules[j];
      Capsule& w = state.world_capsule[g];
      w.a = r * local.a + origin;
      w.b = r * local.b + origin;
      w.radius_m = local.radius_m;
      box.extend(capsule_box(w));
      // Per-capsule culling data for the narrow phase, computed once per step.
      state.capsule_box[g] = capsule_box(w, reach);
      state.capsule_sphere[g] << 0.5 * (w.a + w.b), 0.5 * (w.b - w.a).norm() + local.radius_m;
    }
    // Half the reach on each side, so bodies closer than the contact offset (or the depenetration
    // margin) are paired.
    box.lo -= Vec3::Constant(0.5 * reach);
    box.hi += Vec3::Constant(0.5 * reach);
    state.body_box[static_cast<size_t>(c)] = box;
  });

  for (int c = 0; c < n; ++c) state.sweep_order[static_cast<size_t>(c)] = c;
  std::sort(state.sweep_order.begin(), state.sweep_order.end(), [&](int a, int b) {
    const double xa = state.body_box[static_cast<size_t>(a)].lo.x(),
                 xb = state.body_box[static_cast<size_t>(b)].lo.x();
    return xa < xb || (xa == xb && a < b);
  });
  state.body_pairs.clear();
  for (size_t i = 0; i < state.sweep_order.size(); ++i) {
    const int a = state.sweep_order[i];
    const Aabb& box_a = state.body_box[static_cast<size_t>(a)];
    for (size_t k = i + 1; k < state.sweep_order.size(); ++k) {
      const int b = state.sweep_order[k];
      const Aabb& box_b = state.body_box[static_cast<size_t>(b)];
      if (box_b.lo.x() > box_a.hi.x()) break;
      if (box_a.overlaps(box_b)) state.body_pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  // A canonical order (independent of ties in the sweep) for the narrow phase and its output.
  std::sort(state.body_pairs.begin(), state.body_pairs.end());
  state.stats.body_pairs = static_cast<int>(state.body_pairs.size());
}

}  // namespace crowdlab
