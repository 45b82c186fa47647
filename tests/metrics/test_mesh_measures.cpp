// Mesh-level overlap and proxy coverage (issue 27; framework/metrics/mesh_overlap.hpp, proxy_coverage.hpp,
// core/triangle_tree.hpp) on box and ring meshes whose answers are known in closed form, and capsules
// grown to bound a dressed MPFB2 body's rendered mesh (body/cover_capsules.hpp).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "framework/body/cover_capsules.hpp"
#include "framework/body/mpfb2_body.hpp"
#include "framework/body/mpfb2_model.hpp"
#include "framework/body/mpfb2_outfit.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "framework/core/skeleton.hpp"
#include "framework/core/surface_kind_name.hpp"
#include "framework/core/triangle_tree.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/mesh_overlap.hpp"
#include "framework/metrics/proxy_coverage.hpp"
#include "framework/metrics/surfaces_inside.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_mesh_measures {

using namespace crowdlab;

namespace {

constexpr int kFrames = 60;  // 2 s at 30 fps

/// The surface of a box (centre c, half extents h) as six n x n grids, counter-clockwise from outside
/// (each face has its own vertices, so a face's vertex normals are the face's normal).
void add_box(const Vec3& c, const Vec3& h, int n, std::vector<Vec3>& v, std::vector<Eigen::Vector3i>& t) {
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1}) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      const int base = static_cast<int>(v.size());
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
          Vec3 p = c;
          p[axis] += side * h[axis];
          p[u] += h[u] * (-1.0 + 2.0 * i / n);
          p[w] += h[w] * (-1.0 + 2.0 * j / n);
          v.push_back(p);
        }
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const int a = base + i * (n + 1) + j, b = a + n + 1;
          // (u, w, axis) is right-handed, so u x w points along +axis: flip the winding on the - side.
          if (side > 0) {
            t.emplace_back(a, b, b + 1);
            t.emplace_back(a, b + 1, a + 1);
          } else {
            t.emplace_back(a, b + 1, b);
            t.emplace_back(a, a + 1, b + 1);
          }
        }
    }
}

/// A mesh skinned wholly to the pelvis, given in the character frame of a rest pose whose pelvis is at
/// `pelvis` (so a pose with root position r moves every vertex by r - pelvis).
std::shared_ptr<SkinnedMesh> pelvis_mesh(std::vector<Vec3> v, std::vector<Eigen::Vector3i> t,
                                         const Vec3& pelvis) {
  auto m = std::make_shared<SkinnedMesh>();
  m->rest_vertices_m = std::move(v);
  m->triangles = std::move(t);
  m->rest_normals = vertex_normals(m->rest_vertices_m, m->triangles);
  m->joints.assign(m->rest_vertices_m.size(), {0, 0, 0, 0});
  m->weights.assign(m->rest_vertices_m.size(), {1.0, 0.0, 0.0, 0.0});
  m->region.assign(m->rest_vertices_m.size(), 0);
  m->rest_joints_m[kPelvis] = pelvis;
  return m;
}

/// A character standing still in the rest pose with its pelvis at `root`, carrying `mesh`, 2 s.
CharacterAnimation still(const BodyShape& shape, const Vec3& root, std::shared_ptr<const SkinnedMesh> mesh) {
  CharacterAnimation c;
  c.name = "c";
  c.shape = shape;
  c.mesh = std::move(mesh);
  Pose p = Pose::rest(shape);
  p.root_position_m = root;
  c.frames.assign(kFrames, p);
  return c;
}

/// Depth of p inside the box (centre c, half extents h): > 0 inside.
double box_depth(const Vec3& p, const Vec3& c, const Vec3& h) {
  return (h - (p - c).cwiseAbs()).minCoeff();
}

}  // namespace

TEST_CASE("the triangle tree gives the exact signed distance to a closed box") {
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  add_box(Vec3::Zero(), Vec3::Constant(0.5), 4, v, t);
  const TriangleTree tree(v, t);
  const std::vector<Vec3> normals = vertex_normals(v, t);
  CHECK(tree.signed_distance({0.2, 0.0, 0.0}, normals) == Approx(-0.3));
  CHECK(tree.signed_distance({0.0, -0.45, 0.1}, normals) == Approx(-0.05));
  CHECK(tree.signed_distance({0.9, 0.0, 0.0}, normals) == Approx(0.4));
  CHECK(tree.signed_distance({0.8, 0.8, 0.1}, normals) == Approx(std::sqrt(0.18)));    // an edge
  CHECK(tree.signed_distance({-0.8, 0.8, -0.8}, normals) == Approx(std::sqrt(0.27)));  // a corner
  const TriangleHit hit = tree.closest({0.1, 0.2, 3.0});
  CHECK((hit.point - Vec3(0.1, 0.2, 0.5)).norm() == Approx(0.0).margin(1e-12));
  CHECK(hit.distance == Approx(2.5));
}

TEST_CASE("the inside test ignores the far side of an open sheet's rim") {
  // One face of a box alone: the square y = 0.5, |x|, |z| <= 0.5, facing +y.
  std::vector<Vec3> box;
  std::vector<Eigen::Vector3i> tb;
  add_box(Vec3::Zero(), Vec3::Constant(0.5), 2, box, tb);
  const std::vector<Vec3> v(box.begin() + 3 * 9, box.begin() + 4 * 9);  // the +y face's 3 x 3 grid
  std::vector<Eigen::Vector3i> t;
  for (const Eigen::Vector3i& tri : tb)
    if (tri.minCoeff() >= 27 && tri.maxCoeff() < 36) t.push_back(tri - Eigen::Vector3i::Constant(27));
  REQUIRE(t.size() == 8);
  REQUIRE(v[0].y() == 0.5);
  const TriangleTree tree(v, t);
  const std::vector<Vec3> normals = vertex_normals(v, t);
  const std::vector<bool> rim = boundary_vertices(static_cast<int>(v.size()), t);
  CHECK(std::count(rim.begin(), rim.end(), true) == 8);  // all but the centre
  const Vec3 beside(0.9, 0.2, 0.0);  // below and beyond the rim: the closest point is on the rim
  CHECK(tree.signed_distance(beside, normals) < 0.0);  // what the normal alone would say
  CHECK(tree.signed_distance(beside, normals, rim) == Approx(0.5));
  CHECK(tree.signed_distance({0.0, 0.3, 0.1}, normals, rim) == Approx(-0.2));  // under the sheet
}

TEST_CASE("the triangle tree's ray query meets a box from inside and misses it from outside looking away") {
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  add_box(Vec3::Zero(), Vec3::Constant(0.5), 4, v, t);
  const TriangleTree tree(v, t);
  const double far = std::numeric_limits<double>::infinity();
  for (const Vec3& dir : {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0.6, 0.0, 0.8), Vec3(-0.48, 0.6, 0.64)})
    CHECK(tree.ray_hits({0.1, 0.2, -0.1}, dir, 0.0, far));            // every ray from inside meets the box
  CHECK(tree.ray_hits({0.0, 0.0, 0.0}, {1, 0, 0}, 0.0, far));         // through a grid vertex of the face
  CHECK(tree.ray_hits({2.0, 0.1, 0.1}, {-1, 0, 0}, 0.0, far));        // from outside, toward the box
  CHECK_FALSE(tree.ray_hits({2.0, 0.1, 0.1}, {1, 0, 0}, 0.0, far));   // looking away
  CHECK_FALSE(tree.ray_hits({2.0, 0.1, 0.1}, {-1, 0, 0}, 0.0, 1.4));  // the box is 1.5 away
  CHECK_FALSE(tree.ray_hits({2.0, 0.1, 0.1}, {0, 1, 0}, 0.0, far));   // passing beside it
}

TEST_CASE("the inside test needs the surface beyond the point: a face turned inward gives no false inside") {
  // Box b's +x face is wound the wrong way round (as on a fold of a shoe's collar, its outer face turning
  // into its lining): its normal points into the box, so the closest-point sign alone puts points just
  // outside that face inside b (session 25, the D5 concert: feet 15 cm "deep" beside a neighbour's shoe).
  const BodyShape shape = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const Vec3 pelvis(0.0, shape.pelvis_height_m(), 0.0);
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  add_box(pelvis, Vec3::Constant(0.5), 4, v, t);
  std::vector<Eigen::Vector3i> flipped = t;
  int turned = 0;
  for (Eigen::Vector3i& tri : flipped)
    if (v[static_cast<size_t>(tri[0])].x() == pelvis.x() + 0.5 &&
        v[static_cast<size_t>(tri[1])].x() == pelvis.x() + 0.5 &&
        v[static_cast<size_t>(tri[2])].x() == pelvis.x() + 0.5) {
      std::swap(tri[1], tri[2]);
      ++turned;
    }
  REQUIRE(turned == 32);
  // And a small closed box off b's corner (a hand), so that b's bounding box reaches past the turned face
  // and takes in the point tested below: only points within b's box are tested.
  add_box(pelvis + Vec3(0.95, 0.4, 0.4), Vec3::Constant(0.05), 1, v, flipped);
  add_box(pelvis + Vec3(0.95, 0.4, 0.4), Vec3::Constant(0.05), 1, v, t);
  v.resize(v.size() - 24);  // the second copy's vertices: t indexes the first copy's (same positions)
  for (size_t i = t.size() - 12; i < t.size(); ++i) t[i] -= Eigen::Vector3i::Constant(24);
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  crowd.characters.push_back(still(shape, pelvis, pelvis_mesh(v, flipped, pelvis)));
  {  // a neighbour whose box meets b's, so that b is tested at all (FrameSurfaces)
    std::vector<Vec3> nv;
    std::vector<Eigen::Vector3i> nt;
    add_box(pelvis, Vec3::Constant(0.1), 1, nv, nt);
    crowd.characters.push_back(still(shape, pelvis + Vec3(0.0, 0.0, 0.55), pelvis_mesh(nv, nt, pelvis)));
  }
  const FrameSurfaces surfaces(crowd, 0);
  const Vec3 outside = pelvis + Vec3(0.6, 0.05, 0.1);  // 10 cm off the turned face
  {                                                    // what the sign alone says
    const std::vector<Vec3> normals = vertex_normals(surfaces.meshes()[0].vertices, flipped);
    const TriangleTree tree(surfaces.meshes()[0].vertices, flipped);
    REQUIRE(tree.signed_distance(outside, normals) == Approx(-0.1));
    REQUIRE(surfaces.meshes()[0].bounds.contains(outside));
  }
  int by = 7;
  CHECK(surfaces.inside_depth(outside, -1, 0.2, &by) == 0.0);
  CHECK(by == -1);
  // Points inside near the other faces are still inside, at their depth.
  CHECK(surfaces.inside_depth(pelvis + Vec3(-0.35, 0.05, 0.1), -1, 0.2, &by) == Approx(0.15));
  CHECK(by == 0);
  CHECK(surfaces.inside_depth(pelvis + Vec3(0.1, -0.42, 0.0), -1, 0.2) == Approx(0.08));
  // And with the face wound right, the same outside point is outside by the sign too.
  const CrowdAnimation right = [&] {
    CrowdAnimation c = crowd;
    c.characters[0].mesh = pelvis_mesh(v, t, pelvis);
    return c;
  }();
  CHECK(FrameSurfaces(right, 0).inside_depth(outside, -1, 0.2) == 0.0);
}

TEST_CASE("mesh overlap: the vertices of two overlapping boxes inside each other, with their depths") {
  const BodyShape shape = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const Vec3 pelvis(0.0, shape.pelvis_height_m(), 0.0);
  const Vec3 ha(0.5, 0.5, 0.5), hb(0.5, 0.6, 0.6);
  std::vector<Vec3> va, vb;
  std::vector<Eigen::Vector3i> ta, tb;
  add_box(pelvis, ha, 10, va, ta);
  add_box(pelvis, hb, 10, vb, tb);
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  const Vec3 ca = pelvis, cb = pelvis + Vec3(0.75, 0.0, 0.0);  // b spans x in [0.25, 1.25]
  crowd.characters.push_back(still(shape, ca, pelvis_mesh(va, ta, pelvis)));
  crowd.characters.push_back(still(shape, cb, pelvis_mesh(vb, tb, pelvis)));
  crowd.characters.push_back(still(shape, pelvis + Vec3(5.0, 0.0, 0.0), nullptr));  // no mesh: not counted

  // The answer from the boxes themselves: a's vertices inside box b and b's inside box a.
  std::vector<double> depths;
  for (const Vec3& p : va)
    if (box_depth(p, cb, hb) > 0) depths.push_back(box_depth(p, cb, hb));
  for (const Vec3& p : vb)
    if (box_depth(p - pelvis + cb, ca, ha) > 0) depths.push_back(box_depth(p - pelvis + cb, ca, ha));
  REQUIRE(depths.size() > 50);
  const double fraction = static_cast<double>(depths.size()) / static_cast<double>(va.size() + vb.size());

  const MeshOverlap q = measure_mesh_overlap(crowd, 0, 0.5, 1.0);  // no depth bound (boxes are not bodies)
  CHECK(q.frames == 4);
  // The depth bound (kMaxBodyDepth_m, 0.2 m, by default) counts deeper vertices as outside (the depths
  // here are multiples of 5 cm: a bound between them).
  const long shallow = std::count_if(depths.begin(), depths.end(), [](double d) { return d <= 0.17; });
  CHECK(measure_mesh_overlap(crowd, 0, 0.5, 0.17).inside_samples == 4 * shallow);
  CHECK(shallow < static_cast<long>(depths.size()));  // 2 s, one frame every 0.5 s
  CHECK(q.sampled_frames == std::vector<int>{0, 15, 30, 45});
  CHECK(q.fraction_mean == Approx(fraction).epsilon(1e-12));
  CHECK(q.fraction_max == Approx(fraction).epsilon(1e-12));
  CHECK(q.inside_samples == 4 * static_cast<long>(depths.size()));
  CHECK(q.depth_max_m == Approx(*std::max_element(depths.begin(), depths.end())).epsilon(1e-9));
  CHECK(q.depth_max_m == Approx(0.25).epsilon(1e-9));  // a's face x = 0.5 is 0.25 deep in b
  std::vector<double> all;
  for (int k = 0; k < 4; ++k) all.insert(all.end(), depths.begin(), depths.end());
  CHECK(q.depth_p99_m == Approx(nearest_rank_quantile(all, 0.99)).epsilon(1e-9));
  CHECK(q.worst_frame == 0);

  // Moved apart (b at x = 1.1: 0.1 m gap), nothing is inside.
  for (Pose& p : crowd.characters[1].frames) p.root_position_m.x() = 1.1;
  const MeshOverlap apart = measure_mesh_overlap(crowd);
  CHECK(apart.fraction_max == 0.0);
  CHECK(apart.inside_samples == 0);
  CHECK(apart.worst_character == -1);

  // Without meshes there is nothing to measure.
  crowd.characters[0].mesh = nullptr;
  crowd.characters[1].mesh = nullptr;
  CHECK(measure_mesh_overlap(crowd).frames == 0);
}

TEST_CASE("proxy coverage: the share of vertices within 5 mm of the capsules and how far the rest are") {
  BodyShape shape = make_procedural_body({Sex::kMale, 1.75, 1.0});
  // One capsule that matters: the pelvis, axis x in [-0.1, 0.1], r = 0.2; every other bone a 1 mm ball
  // at the pelvis (inside it), so the distance outside the proxies is the pelvis capsule's.
  const auto joints = joint_positions(shape, Pose::rest(shape));
  const double r = 0.2;
  for (int j = 0; j < kJointCount; ++j) {
    const Vec3 at = joints[kPelvis] - joints[static_cast<size_t>(j)];
    shape.capsules[static_cast<size_t>(j)] = {at, at, 0.001};
  }
  shape.capsules[kPelvis] = {Vec3(-0.1, 0, 0), Vec3(0.1, 0, 0), r};
  const Vec3 pelvis = joints[kPelvis];
  std::vector<Vec3> v;
  for (int i = 0; i < 96; ++i) {  // on the cylinder
    const double a = 2 * std::numbers::pi * i / 96;
    v.push_back(pelvis + Vec3(0.1 * (i % 3 - 1), r * std::cos(a), r * std::sin(a)));
  }
  v.push_back(pelvis + Vec3(0.0, r + 0.003, 0.0));       // 3 mm out: within the tolerance
  v.push_back(pelvis + Vec3(0.05, 0.0, -r - 0.003));     // 3 mm out
  v.push_back(pelvis + Vec3(0.1 + r + 0.02, 0.0, 0.0));  // 20 mm beyond the cap
  v.push_back(pelvis + Vec3(0.0, -r - 0.05, 0.0));       // 50 mm out, and it is hair
  auto mesh = pelvis_mesh(v, {}, pelvis);
  mesh->surface.assign(v.size(), static_cast<std::uint8_t>(SurfaceKind::kSkin));
  mesh->surface.back() = static_cast<std::uint8_t>(SurfaceKind::kHair);

  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  crowd.characters.push_back(still(shape, pelvis + Vec3(2.0, 0.0, 1.0), mesh));
  const ProxyCoverage q = measure_proxy_coverage(crowd);
  CHECK(q.frames == 4);
  CHECK(q.vertex_samples == 400);
  CHECK(q.within_share == Approx(0.98));
  CHECK(q.outside_max_m == Approx(0.05).epsilon(1e-9));
  CHECK(q.outside_p99_m == Approx(0.02).epsilon(1e-9));  // nearest rank 0.99 * 399 -> the 396th of 400
  CHECK(q.worst_character == 0);
  CHECK(q.within_share_by_surface[static_cast<size_t>(SurfaceKind::kHair)] == 0.0);
  CHECK(q.within_share_by_surface[static_cast<size_t>(SurfaceKind::kSkin)] == Approx(98.0 / 99.0));
  CHECK(q.within_share_by_surface[static_cast<size_t>(SurfaceKind::kShoes)] == -1.0);

  // Capsules grown by 5 cm cover everything.
  for (Capsule& c : crowd.characters[0].shape.capsules) c.radius_m += 0.05;
  const ProxyCoverage grown = measure_proxy_coverage(crowd);
  CHECK(grown.within_share == 1.0);
  CHECK(grown.outside_max_m == 0.0);
  CHECK(grown.worst_character == -1);
}

TEST_CASE("correction quality leaves the mesh-level measures out when asked, and nothing else") {
  // Two interpenetrating boxes carried by two still characters whose capsules overlap too.
  const BodyShape shape = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const Vec3 pelvis(0.0, shape.pelvis_height_m(), 0.0);
  std::vector<Vec3> v;
  std::vector<Eigen::Vector3i> t;
  add_box(pelvis, Vec3(0.3, 0.3, 0.3), 6, v, t);
  const auto box = pelvis_mesh(v, t, pelvis);
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  crowd.characters.push_back(still(shape, pelvis, box));
  crowd.characters.push_back(still(shape, pelvis + Vec3(0.3, 0.0, 0.0), box));

  const CorrectionQuality all = measure_correction_quality(crowd, crowd);
  const CorrectionQuality cheap = measure_correction_quality(crowd, crowd, 0, 1, false);
  REQUIRE(all.mesh_overlap.frames == 4);  // 2 s sampled every 0.5 s
  CHECK(all.mesh_overlap.inside_samples > 0);
  CHECK(all.proxy_coverage.frames == 4);
  CHECK(cheap.mesh_overlap.frames == 0);
  CHECK(cheap.mesh_overlap.inside_samples == 0);
  CHECK(cheap.proxy_coverage.frames == 0);
  // The capsule measures are the same either way.
  CHECK(all.depth_samples > 0);
  CHECK(cheap.depth_samples == all.depth_samples);
  CHECK(cheap.depth_p99_m == all.depth_p99_m);
  CHECK(cheap.rotation_dev_p99_deg == all.rotation_dev_p99_deg);
}

namespace {

/// A dressed male MPFB2 body (skin, outfit, hair, shoes, eyes), built once.
const Mpfb2Body& dressed_body() {
  static const Mpfb2Body body = [] {
    const auto model = Mpfb2Model::load(shipped_mpfb2_dir());
    const auto wardrobe =
        Mpfb2Wardrobe::load(default_makehuman_dir(), static_cast<int>(model->base().vertices.size()));
    const Mpfb2Outfit outfit = sample_mpfb2_outfit(*wardrobe, Sex::kMale, 3);
    Mpfb2ShapeParams params;
    params.gender = 1.0;
    return make_mpfb2_body(*model, params, &outfit);
  }();
  return body;
}

}  // namespace

TEST_CASE("the inside test on a dressed MPFB2 body: its joints are inside, points around it outside") {
  const Mpfb2Body& body = dressed_body();
  const Pose rest = Pose::rest(body.shape);
  const std::vector<Vec3> v = skin_vertices(body.mesh, forward_kinematics(body.shape, rest));
  const TriangleTree tree(v, body.mesh.triangles);
  const std::vector<Vec3> normals = vertex_normals(v, body.mesh.triangles);
  const auto joints = joint_positions(body.shape, rest);
  for (int j : {kPelvis, kSpine1, kSpine2, kSpine3, kHead, kLeftHip, kRightHip, kLeftKnee, kRightKnee,
                kLeftElbow, kRightElbow}) {
    INFO(joint_name(j));
    CHECK(tree.signed_distance(joints[static_cast<size_t>(j)], normals) < -0.02);
  }
  for (const Vec3& off : {Vec3(0, 0, 0.4), Vec3(0, 0, -0.4), Vec3(0.5, 0, 0), Vec3(0, 1.2, 0)})
    CHECK(tree.signed_distance(joints[kPelvis] + off, normals) > 0.05);

  // Two of them side by side: 10 cm apart they interpenetrate, 3 m apart (beyond the T-posed arms) not.
  auto mesh = std::make_shared<const SkinnedMesh>(body.mesh);
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  crowd.characters.push_back(still(body.shape, rest.root_position_m, mesh));
  crowd.characters.push_back(still(body.shape, rest.root_position_m + Vec3(0.1, 0, 0), mesh));
  const MeshOverlap close = measure_mesh_overlap(crowd, 0, 10.0);
  CHECK(close.fraction_mean > 0.2);
  CHECK(close.depth_max_m > 0.05);
  for (Pose& p : crowd.characters[1].frames) p.root_position_m.x() += 2.9;
  CHECK(measure_mesh_overlap(crowd, 0, 10.0).inside_samples == 0);
}

TEST_CASE("capsules grown to a dressed MPFB2 body bound its rendered mesh in the rest pose") {
  const Mpfb2Body& body = dressed_body();
  auto mesh = std::make_shared<const SkinnedMesh>(body.mesh);
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  crowd.characters.push_back(still(body.shape, Pose::rest(body.shape).root_position_m, mesh));
  const ProxyCoverage before = measure_proxy_coverage(crowd, 0, 10.0);  // one frame
  REQUIRE(before.frames == 1);
  // The volume-fitted capsules leave much of the skin and more of the clothes and hair outside.
  CHECK(before.within_share < 0.9);
  CHECK(before.outside_max_m > 0.02);

  BodyShape grown = body.shape;
  const CoverReport report = cover_mesh_with_capsules(grown, *mesh);
  CHECK(report.within_before == Approx(before.within_share).margin(1e-12));
  CHECK(report.within_after == 1.0);
  for (int j = 0; j < kJointCount; ++j) CHECK(report.growth_m[static_cast<size_t>(j)] >= 0.0);
  crowd.characters[0].shape = grown;
  const ProxyCoverage after = measure_proxy_coverage(crowd, 0, 10.0);
  CHECK(after.within_share == 1.0);
  CHECK(after.outside_max_m <= kProxyCoverageTolerance_m + 1e-12);
}

TEST_CASE("capsules fitted per surface bound each surface to its tolerance, above the floor") {
  const Mpfb2Body& body = dressed_body();
  const SkinnedMesh& mesh = body.mesh;
  BodyShape uniform = body.shape, fitted = body.shape, unfloored = body.shape;
  cover_mesh_with_capsules(uniform, mesh);
  // Without the floor cap (the default) every bounded vertex is taken in.
  const CoverReport unfloored_report =
      fit_capsules_to_mesh(unfloored, mesh, SurfaceTolerances::per_surface(), true);
  CHECK(unfloored_report.bounded_within_after == 1.0);
  CHECK(unfloored.capsule_volume_sum_m3() < uniform.capsule_volume_sum_m3());
  SurfaceTolerances tol = SurfaceTolerances::per_surface();
  tol.keep_above_floor = true;
  const CoverReport report = fit_capsules_to_mesh(fitted, mesh, tol, true);
  // With it, checked here from the rest-pose mesh itself: no capsule reaches below the floor further than
  // it did unfitted, and every bounded vertex is within its surface's tolerance but for what a capped
  // bone misses (soles aside).
  const BoneTransforms bones = forward_kinematics(fitted, Pose::rest(fitted));
  const std::vector<Vec3> v = skin_vertices(mesh, bones);
  const WorldCapsules caps = world_capsules(fitted, bones);
  const WorldCapsules before = world_capsules(body.shape, bones);
  double lowest = 1e300, max_miss = 0.0;
  for (const Vec3& p : v) lowest = std::min(lowest, p.y());
  const auto bottom = [](const Capsule& c) { return std::min(c.a.y(), c.b.y()) - c.radius_m; };
  for (size_t j = 0; j < kJointCount; ++j) {
    CAPTURE(j);
    CHECK(bottom(caps[j]) >= std::min(lowest, bottom(before[j])) - 1e-9);
    max_miss = std::max(max_miss, report.floor_miss_m[j]);
  }
  CHECK(max_miss < 0.03);  // a shoe's edge, not a body part
  int soles = 0, bounded = 0, missed = 0;
  for (size_t k = 0; k < v.size(); ++k) {
    const auto kind = static_cast<SurfaceKind>(mesh.surface[k]);
    if (kind == SurfaceKind::kShoes && v[k].y() - lowest <= tol.sole_height_m) {
      ++soles;
      continue;
    }
    ++bounded;
    const double out = outside_capsules_m(v[k], caps), t = tol.tolerance_m[static_cast<size_t>(kind)];
    missed += out > t + 1e-9;
    if (out <= t + 1e-9) continue;
    CAPTURE(k, surface_kind_name(kind), out);
    CHECK(v[k].y() - lowest < 0.1);  // only the feet (shoes, the skin inside them) meet the floor cap
    CHECK(out <= t + max_miss + 1e-6);
  }
  CHECK(soles > 0);
  CHECK(report.bounded_within_after == Approx(1.0 - static_cast<double>(missed) / bounded).margin(1e-9));
  // Moving the axes toward the surface they must take in: less capsule volume than growing radii alone,
  // and the head (face in front of it) moved forward (+Z in the rest frame).
  CHECK(fitted.capsule_volume_sum_m3() < uniform.capsule_volume_sum_m3());
  CHECK(report.shift_m[kHead] > 0.0);
  CHECK(fitted.capsules[kHead].a.z() > body.shape.capsules[kHead].a.z());
}

}  // namespace test_mesh_measures
