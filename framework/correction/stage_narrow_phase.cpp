// Narrow phase (seed 000 §3.4): for each candidate capsule pair, "a faster sphere-sphere culling test"
// and then the exact capsule-capsule penetration (core capsule_contact: segment-segment closest points,
// robust for parallel and degenerate axes, normal defined when the axes intersect). Inter-body pairs
// come from the broad phase; intra-body pairs skip those touching in T-pose; every capsule end sphere
// is tested against the ground y = 0; capsules are tested against the environment's sample points.
#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "framework/correction/corrector_step.hpp"
#include "framework/correction/environment_box_contact.hpp"

namespace crowdlab {
namespace {

/// Bounding spheres (centre at the axis midpoint, radius half-length + capsule radius; precomputed by
/// the broad phase) closer than the contact offset.
bool spheres_overlap(const Vec4& a, const Vec4& b, double offset) {
  const double reach = a.w() + b.w() + offset;
  return (a.head<3>() - b.head<3>()).squaredNorm() < reach * reach;
}

/// The contact of bones ga, gb from their capsule contact; offset: contact offset (m) added to the
/// depth (inter-body contacts only; see CorrectorParams).
Contact make_contact(int ga, int gb, double k, double offset, const CapsuleContact& cc) {
  Contact out;
  out.bone_a = ga;
  out.bone_b = gb;
  out.depth_m = cc.depth_m + offset;
  out.stiffness = k;
  out.normal = cc.normal;
  out.point_a = cc.point_a;
  out.point_b = cc.point_b;
  return out;
}

bool make_capsule_contact(const CorrectorState& state, int ga, int gb, double k, double offset,
                          Contact& out) {
  if (!spheres_overlap(state.capsule_sphere[static_cast<size_t>(ga)],
                       state.capsule_sphere[static_cast<size_t>(gb)], offset))
    return false;
  const CapsuleContact cc = capsule_contact(state.world_capsule[static_cast<size_t>(ga)],
                                            state.world_capsule[static_cast<size_t>(gb)]);
  if (!(cc.depth_m + offset > 0.0)) return false;
  out = make_contact(ga, gb, k, offset, cc);
  return true;
}

/// Body pair (ci, cj)'s contacts, near capsule pairs and (when release_free_joints) the bones of each
/// within free_joint_margin_m of the other, `touched` (stage_contact_scope reads it). The margin test
/// needs the capsule distance of every near pair, which the contact test computes anyway for the pairs
/// within the contact offset: computing it once here, in parallel over pairs, took the serial pass
/// stage_contact_scope made over the near pairs (6 % of the 60-character step, session 20) off the step.
void body_pair_contacts(const CorrectorModel& model, const CorrectorState& state, int ci, int cj,
                        std::vector<Contact>& out, NearCapsulePairs& near, std::array<BoneMask, 2>& touched) {
  out.clear();
  near.clear();
  touched = {0, 0};
  const bool scope = model.params.release_free_joints;
  const double margin = model.params.free_joint_margin_m;
  const Aabb& box_i = state.body_box[static_cast<size_t>(ci)];
  const Aabb& box_j = state.body_box[static_cast<size_t>(cj)];
  int list_i[kJointCount], list_j[kJointCount];
  int ni = 0, nj = 0;
  const double offset = model.params.contact_offset_m;
  // The capsule pairs the depenetration pass tests (stage_depenetrate.cpp) are listed here too: those
  // whose bounding spheres come within its margin (the boxes were grown by the same reach).
  const double reach = detection_reach(model.params);
  for (int b = 0; b < kJointCount; ++b) {
    if (state.capsule_box[static_cast<size_t>(ci * kJointCount + b)].overlaps(box_j)) list_i[ni++] = b;
    if (state.capsule_box[static_cast<size_t>(cj * kJointCount + b)].overlaps(box_i)) list_j[nj++] = b;
  }
  const double k = model.params.contact_stiffness;
  for (int x = 0; x < ni; ++x)
    for (int y = 0; y < nj; ++y) {
      const int ga = ci * kJointCount + list_i[x], gb = cj * kJointCount + list_j[y];
      const Vec4& sa = state.capsule_sphere[static_cast<size_t>(ga)];
      const Vec4& sb = state.capsule_sphere[static_cast<size_t>(gb)];
      if (!spheres_overlap(sa, sb, reach)) continue;
      near.push_back({static_cast<std::uint8_t>(list_i[x]), static_cast<std::uint8_t>(list_j[y])});
      const bool contact = spheres_overlap(sa, sb, offset);
      if (!contact && !scope) continue;
      const CapsuleContact cc = capsule_contact(state.world_capsule[static_cast<size_t>(ga)],
                                                state.world_capsule[static_cast<size_t>(gb)]);
      if (contact && cc.depth_m + offset > 0.0) out.push_back(make_contact(ga, gb, k, offset, cc));
      if (scope && cc.depth_m > -margin) {
        touched[0] |= BoneMask{1} << list_i[x];
        touched[1] |= BoneMask{1} << list_j[y];
      }
    }
}

/// The exact contact of capsule `cap` (bone g) with box `box` (environment_box_contact.hpp): depth =
/// penetration + contact offset.
bool box_contact(const Capsule& cap, int g, const Box& box, const Vec3& root, double k, double offset,
                 Contact& out) {
  EnvironmentBoxContact e;
  if (!environment_box_contact(cap, box, root, -offset, e)) return false;
  out = Contact{};
  out.bone_a = g;
  out.kind = ContactKind::kEnvironment;
  out.stiffness = k;
  out.point_a = e.axis_point;
  out.normal = e.normal;
  out.depth_m = e.penetration_m + offset;
  return true;
}

void single_body_contacts(const CorrectorModel& model, const CorrectorState& state, int ci,
                          std::vector<Contact>& out, std::array<int, 3>& counts) {
  out.clear();
  const CorrectorBody& body = model.bodies[static_cast<size_t>(ci)];
  const int base = ci * kJointCount;
  Contact c;
  // Intra-body (self) contacts.
  for (const auto& [i, j] : body.self_pairs) {
    const int ga = base + i, gb = base + j;
    if (make_capsule_contact(state, ga, gb, model.params.intra_body_contact_stiffness, 0.0, c)) {
      c.kind = ContactKind::kIntraBody;
      out.push_back(c);
    }
  }
  counts[0] = static_cast<int>(out.size());
  // Ground: each capsule end sphere against y = 0, normal +Y.
  if (model.ground_plane) {
    for (int b = 0; b < kJointCount; ++b) {
      const Capsule& cap = state.world_capsule[static_cast<size_t>(base + b)];
      for (const Vec3* end : {&cap.a, &cap.b}) {
        const double depth = cap.radius_m - end->y();
        if (depth <= 0.0) continue;
        c = Contact{};
        c.bone_a = base + b;
        c.depth_m = depth;
        c.stiffness = model.params.ground_stiffness;
        c.normal = Vec3::UnitY();
        c.point_a = *end;
        c.kind = ContactKind::kGround;
        out.push_back(c);
      }
    }
  }
  counts[1] = static_cast<int>(out.size()) - counts[0];
  // Environment: sample points inside a capsule push it out along (axis point - sample point).
  if (!model.environment.empty() &&
      state.body_box[static_cast<size_t>(ci)].overlaps(model.environment.bounds())) {
    for (int b = 0; b < kJointCount; ++b) {
      const Capsule& cap = state.world_capsule[static_cast<size_t>(base + b)];
      const size_t first = out.size();
      model.environment.query(capsule_box(cap), [&](int index) {
        const Vec3& q = model.environment.points()[static_cast<size_t>(index)];
        const SegmentClosestPoints cp = segment_closest_points(cap.a, cap.b, q, q);
        const double depth = cap.radius_m - cp.distance_m;
        if (depth <= 0.0) return;
        c = Contact{};
        c.bone_a = base + b;
        c.depth_m = depth;
        if (cp.distance_m > 1e-9)
          c.normal = (cp.point_on_p - q) / cp.distance_m;
        else  // the sample lies on the axis: any direction across the axis separates
          c.normal = (cap.b - cap.a).squaredNorm() > 1e-18 ? any_perpendicular(cap.b - cap.a) : Vec3::UnitY();
        c.point_a = cp.point_on_p;
        c.kind = ContactKind::kEnvironment;
        out.push_back(c);
      });
      // The capsule's environment stiffness is shared by the points it touches, so the push does not
      // depend on the sampling density.
      const size_t count = out.size() - first;
      for (size_t i = first; i < out.size(); ++i)
        out[i].stiffness = model.params.environment_stiffness / static_cast<double>(count);
    }
  }
  // Environment boxes: exact capsule-box contacts (box_contact).
  for (size_t k = 0; k < model.environment_boxes.size(); ++k) {
    if (!state.body_box[static_cast<size_t>(ci)].overlaps(model.environment_box_bounds[k])) continue;
    const Vec3 root = state.world_capsule[static_cast<size_t>(base)].a;
    for (int b = 0; b < kJointCount; ++b) {
      const Capsule& cap = state.world_capsule[static_cast<size_t>(base + b)];
      if (!capsule_box(cap, model.params.contact_offset_m).overlaps(model.environment_box_bounds[k]))
        continue;
      if (box_contact(cap, base + b, model.environment_boxes[k], root, model.params.environment_stiffness,
                      model.params.contact_offset_m, c))
        out.push_back(c);
    }
  }
  counts[2] = static_cast<int>(out.size()) - counts[0] - counts[1];
}

}  // namespace

void stage_narrow_phase(const CorrectorModel& model, CorrectorState& state) {
  const int n = model.characters();
  const size_t pairs = state.body_pairs.size();
  if (state.per_pair_contacts.size() < pairs) state.per_pair_contacts.resize(pairs);
  if (state.per_pair_near.size() < pairs) state.per_pair_near.resize(pairs);
  if (state.pair_touched.size() < pairs) state.pair_touched.resize(pairs);
  tbb::parallel_for(size_t{0}, pairs, [&](size_t k) {
    body_pair_contacts(model, state, state.body_pairs[k].first, state.body_pairs[k].second,
                       state.per_pair_contacts[k], state.per_pair_near[k], state.pair_touched[k]);
  });
  tbb::parallel_for(0, n, [&](int c) {
    single_body_contacts(model, state, c, state.per_body_contacts[static_cast<size_t>(c)],
                         state.per_body_counts[static_cast<size_t>(c)]);
  });

  // Gather in a fixed order: per-character contacts (by character), then body pairs (sorted).
  state.contacts.clear();
  StepStats& st = state.stats;
  for (int c = 0; c < n; ++c) {
    const auto& list = state.per_body_contacts[static_cast<size_t>(c)];
    state.contacts.insert(state.contacts.end(), list.begin(), list.end());
    st.intra_body_contacts += state.per_body_counts[static_cast<size_t>(c)][0];
    st.ground_contacts += state.per_body_counts[static_cast<size_t>(c)][1];
    st.environment_contacts += state.per_body_counts[static_cast<size_t>(c)][2];
  }
  for (size_t k = 0; k < pairs; ++k) {
    const auto& list = state.per_pair_contacts[k];
    state.contacts.insert(state.contacts.end(), list.begin(), list.end());
    st.inter_body_contacts += static_cast<int>(list.size());
    for (const Contact& c : list) st.max_penetration_m = std::max(st.max_penetration_m, c.depth_m);
  }

  // Incidence lists (CSR by character) for the deterministic gather in the matrix-vector product.
  auto& offset = state.incidence_offset;
  std::fill(offset.begin(), offset.end(), 0);
  for (const Contact& c : state.contacts) {
    ++offset[static_cast<size_t>(c.bone_a / kJointCount) + 1];
    if (c.bone_b >= 0 && c.bone_b / kJointCount != c.bone_a / kJointCount)
      ++offset[static_cast<size_t>(c.bone_b / kJointCount) + 1];
  }
  for (int c = 0; c < n; ++c) offset[static_cast<size_t>(c) + 1] += offset[static_cast<size_t>(c)];
  state.incidence.resize(static_cast<size_t>(offset[static_cast<size_t>(n)]));
  auto& cursor = state.incidence_cursor;
  std::copy(offset.begin(), offset.end() - 1, cursor.begin());
  for (size_t k = 0; k < state.contacts.size(); ++k) {
    const Contact& c = state.contacts[k];
    const int ca = c.bone_a / kJointCount;
    state.incidence[static_cast<size_t>(cursor[static_cast<size_t>(ca)]++)] = static_cast<int>(2 * k);
    if (c.bone_b >= 0 && c.bone_b / kJointCount != ca)
      state.incidence[static_cast<size_t>(cursor[static_cast<size_t>(c.bone_b / kJointCount)]++)] =
          static_cast<int>(2 * k + 1);
  }
}

}  // namespace crowdlab
