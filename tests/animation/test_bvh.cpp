// BVH import (channel orders, 6-channel joints, errors with line numbers), retargeting (rotated rest
// poses, name maps, the Bandai-Namco clips) and seamless loops.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "framework/animation/animate_crowd.hpp"
#include "framework/animation/bvh.hpp"
#include "framework/animation/clip_loop.hpp"
#include "framework/animation/retarget.hpp"
#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/seed.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_bvh {

using namespace crowdlab;

namespace {
constexpr double kDeg = anim::kPi / 180.0;

const char* kTwoJoint =
    "HIERARCHY\n"
    "ROOT Hips\n"
    "{\n"
    "  OFFSET 0 0 0\n"
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "  JOINT Chest\n"
    "  {\n"
    "    OFFSET 0 10 0\n"
    "    CHANNELS 3 Yrotation Xrotation Zrotation\n"
    "    End Site\n"
    "    {\n"
    "      OFFSET 0 5 0\n"
    "    }\n"
    "  }\n"
    "}\n"
    "MOTION\n"
    "Frames: 2\n"
    "Frame Time: 0.04\n"
    "1 2 3 10 20 30 40 50 60\n"
    "0 0 0 0 0 0 0 0\n"
    "0\n";

std::string expect_error(const std::string& text) {
  try {
    parse_bvh(text, "bad.bvh");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Euler ZXY (degrees) of a rotation: R = Rz(a) Rx(b) Ry(c).
Vec3 euler_zxy_deg(const Quat& q) {
  const Vec3 e = q.toRotationMatrix().eulerAngles(2, 0, 1);
  return e / kDeg;
}

// A BVH of our skeleton with SMPL names whose every joint frame is turned by a random rotation Q_j
// (so the zero pose is contorted, like Bandai-Namco's), carrying `poses` exactly.
std::string contorted_bvh(const BodyShape& s, const std::vector<Pose>& poses, std::uint64_t seed) {
  Rng rng(seed);
  std::array<Quat, kJointCount> q;
  for (auto& r : q)
    r = Quat(Eigen::AngleAxisd(3.0 * uniform01(rng), Vec3::Random().normalized())).normalized();
  std::ostringstream o;
  o.precision(12);
  std::array<std::vector<int>, kJointCount> kids;
  for (int j = 1; j < kJointCount; ++j)
    kids[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])].push_back(j);
  std::vector<int> dfs;  // BVH values follow the hierarchy's depth-first order
  std::function<void(int, int)> write = [&](int j, int depth) {
    dfs.push_back(j);
    const std::string pad(static_cast<size_t>(depth) * 2, ' ');
    o << pad << (j == 0 ? "ROOT " : "JOINT ") << joint_name(j) << "\n" << pad << "{\n";
    const int p = kJointParent[static_cast<size_t>(j)];
    const Vec3 off =
        p < 0
            ? Vec3::Zero()
            : Vec3(q[static_cast<size_t>(p)].conjugate() * s.joint_offsets_m[static_cast<size_t>(j)] * 100.0);
    o << pad << "  OFFSET " << off.x() << " " << off.y() << " " << off.z() << "\n";
    o << pad << "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n";
    for (int c : kids[static_cast<size_t>(j)]) write(c, depth + 1);
    o << pad << "}\n";
  };
  o << "HIERARCHY\n";
  write(0, 0);
  o << "MOTION\nFrames: " << poses.size() << "\nFrame Time: 0.0333333\n";
  for (const Pose& pose : poses) {
    for (int j : dfs) {
      const int p = kJointParent[static_cast<size_t>(j)];
      const Vec3 t = p < 0 ? Vec3(pose.root_position_m * 100.0)
                           : Vec3(q[static_cast<size_t>(p)].conjugate() *
                                  s.joint_offsets_m[static_cast<size_t>(j)] * 100.0);
      // Source local rotation: Q_p^-1 * local * Q_j (source world = our world * Q_j).
      const Quat local = (p < 0 ? Quat::Identity() : q[static_cast<size_t>(p)].conjugate()) *
                         pose.local_rotations[static_cast<size_t>(j)] * q[static_cast<size_t>(j)];
      const Vec3 e = euler_zxy_deg(local);
      o << t.x() << " " << t.y() << " " << t.z() << " " << e.x() << " " << e.y() << " " << e.z() << " ";
    }
    o << "\n";
  }
  return o.str();
}
}  // namespace

TEST_CASE("BVH: channel order, 6-channel joints, values replace offsets, frames over lines") {
  const BvhMotion m = parse_bvh(kTwoJoint, "two.bvh");
  REQUIRE(m.joints.size() == 2);
  CHECK(m.channel_count == 9);
  CHECK(m.frame_count == 2);
  CHECK(m.fps() == Approx(25.0));
  CHECK(m.joints[1].has_end_site);
  const RigidTransform root = m.local_transform(0, 0);
  CHECK((root.translation - Vec3(1, 2, 3)).norm() < 1e-12);
  const Quat expect_root = Quat(Eigen::AngleAxisd(10 * kDeg, Vec3::UnitZ())) *
                           Quat(Eigen::AngleAxisd(20 * kDeg, Vec3::UnitX())) *
                           Quat(Eigen::AngleAxisd(30 * kDeg, Vec3::UnitY()));
  CHECK(root.rotation.angularDistance(expect_root) < 1e-12);
  const Quat expect_chest = Quat(Eigen::AngleAxisd(40 * kDeg, Vec3::UnitY())) *
                            Quat(Eigen::AngleAxisd(50 * kDeg, Vec3::UnitX())) *
                            Quat(Eigen::AngleAxisd(60 * kDeg, Vec3::UnitZ()));
  CHECK(m.local_transform(1, 0).rotation.angularDistance(expect_chest) < 1e-12);
  CHECK((m.local_transform(1, 1).translation - Vec3(0, 10, 0)).norm() < 1e-12);  // no position channels
}

TEST_CASE("BVH: malformed input names file, line and column") {
  const std::string good = kTwoJoint;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  CHECK_THAT(expect_error(replace("OFFSET 0 10 0", "OFFSET 0 x 0")),
             Catch::Contains("bad.bvh:8:14:") && Catch::Contains("number"));
  CHECK_THAT(expect_error(replace("Yrotation Xrotation Zrotation", "Yrotation Wrotation Zrotation")),
             Catch::Contains("bad.bvh:9:") && Catch::Contains("unknown channel 'Wrotation'"));
  CHECK_THAT(expect_error(replace("Frames: 2", "Frames: -2")),
             Catch::Contains("bad.bvh:17:") && Catch::Contains("Frames"));
  CHECK_THAT(expect_error(replace("Frame Time: 0.04", "Frame Time: 0")), Catch::Contains("bad.bvh:18:"));
  CHECK_THAT(expect_error(replace("0 0 0 0 0 0 0 0\n0\n", "0 0 0 0 0 0 0 0\n")),
             Catch::Contains("bad.bvh:20:") && Catch::Contains("truncated"));
  CHECK_THAT(expect_error(replace("0 0 0 0 0 0 0 0\n0\n", "0 0 0 0 0 0 0 0\n0 7\n")),
             Catch::Contains("bad.bvh:21:3:") && Catch::Contains("more motion values"));
  CHECK_THAT(expect_error(replace("40 50 60", "40 nan 60")),
             Catch::Contains("bad.bvh:19:") && Catch::Contains("not finite"));
  CHECK_THAT(expect_error(replace("    End Site", "    Bogus Site")),
             Catch::Contains("bad.bvh:10:") && Catch::Contains("Bogus"));
  CHECK_THAT(expect_error(good.substr(0, 120)),
             Catch::Contains("bad.bvh:") && Catch::Contains("end of file"));
  CHECK_THAT(expect_error(replace("HIERARCHY", "HIERARCHIE")), Catch::Contains("bad.bvh:1:1:"));
  CHECK_THROWS_AS(import_bvh("/nonexistent/x.bvh"), InputError);
}

TEST_CASE("retargeting recovers the motion from a contorted rest pose (joint positions to 1e-6 m)") {
  const BodyShape s = make_procedural_body({Sex::kFemale, 1.66, 1.0});
  Rng rng(3);
  std::vector<Pose> poses(5);
  for (Pose& p : poses) {
    p.root_position_m = Vec3(uniform01(rng), 0.9, uniform01(rng));
    for (auto& r : p.local_rotations)
      r = Quat(Eigen::AngleAxisd(0.5 * uniform01(rng), Vec3::Random().normalized()));
  }
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const BvhMotion m = parse_bvh(contorted_bvh(s, poses, seed), "synthetic.bvh");
    const RetargetedClip c = retarget_bvh(m, s, RetargetOptions{false});  // same feet: no flattening
    CHECK(c.map.convention == SkeletonConvention::kSmpl);
    CHECK(c.scale == Approx(0.01).epsilon(1e-9));
    REQUIRE(c.frames.size() == poses.size());
    // Vertical placement is re-derived from the feet; compare positions relative to the root.
    for (size_t f = 0; f < poses.size(); ++f) {
      const auto a = joint_positions(s, poses[f]), b = joint_positions(s, c.frames[f]);
      for (int j = 0; j < kJointCount; ++j)
        CHECK(((a[static_cast<size_t>(j)] - a[0]) - (b[static_cast<size_t>(j)] - b[0])).norm() < 1e-6);
    }
  }
}

TEST_CASE("name maps: Mixamo, CMU, Bandai-Namco and SMPL skeletons are recognised") {
  auto skeleton = [](std::vector<std::string> names) {
    std::string t = "HIERARCHY\nROOT " + names[0] + "\n{\nOFFSET 0 0 0\nCHANNELS 0\n";
    for (size_t i = 1; i < names.size(); ++i)
      t += "JOINT " + names[i] + "\n{\nOFFSET 0 -1 0\nCHANNELS 0\n}\n";
    return parse_bvh(t + "}\nMOTION\nFrames: 0\nFrame Time: 0.1\n", "names.bvh");
  };
  CHECK(map_joint_names(
            skeleton({"mixamorig:Hips", "mixamorig:LeftUpLeg", "mixamorig:RightUpLeg", "mixamorig:LeftLeg",
                      "mixamorig:RightLeg", "mixamorig:LeftFoot", "mixamorig:RightFoot", "mixamorig:Spine2"}))
            .convention == SkeletonConvention::kMixamo);
  CHECK(map_joint_names(skeleton({"Hips", "LowerBack", "LeftUpLeg", "RightUpLeg", "LeftLeg", "RightLeg",
                                  "LeftFoot", "RightFoot"}))
            .convention == SkeletonConvention::kCmu);
  CHECK(map_joint_names(
            skeleton({"Hips", "UpperLeg_L", "UpperLeg_R", "LowerLeg_L", "LowerLeg_R", "Foot_L", "Foot_R"}))
            .convention == SkeletonConvention::kBandaiNamco);
  CHECK(map_joint_names(skeleton({"Pelvis", "L_Hip", "R_Hip", "L_Knee", "R_Knee", "L_Ankle", "R_Ankle"}))
            .convention == SkeletonConvention::kSmpl);
  CHECK_THROWS_WITH(map_joint_names(skeleton({"Root", "Thing"})),
                    Catch::Contains("names.bvh") && Catch::Contains("pelvis"));
}

TEST_CASE("Bandai-Namco walks retarget to plausible forward walking with alternating feet") {
  const auto dir = test::shared_data("bandai-namco-1");
  if (dir.empty()) return;
  const BodyShape s = make_procedural_body({Sex::kMale, 1.75, 1.0});
  for (const char* file : {"dataset-1_walk_normal_001.bvh", "dataset-1_walk_happy_001.bvh",
                           "dataset-1_walk_tired_001.bvh", "dataset-1_walk-left_normal_001.bvh"}) {
    const BvhMotion m = import_bvh(dir / file);
    RetargetedClip c = retarget_bvh(m, s);
    CHECK(c.map.convention == SkeletonConvention::kBandaiNamco);
    normalize_clip_start(c.frames);
    const size_t n = c.frames.size();
    REQUIRE(n > 60);
    double path = 0, lowest = 1e9, alternations = 0;
    double prev_sign = 0;
    for (size_t f = 0; f < n; ++f) {
      validate_pose(c.frames[f], file);
      const auto jp = joint_positions(s, c.frames[f]);
      for (const Vec3& p : jp) lowest = std::min(lowest, p.y());
      CHECK(jp[kHead].y() > jp[kPelvis].y() + 0.4);
      if (f > 0) path += (c.frames[f].root_position_m - c.frames[f - 1].root_position_m).norm();
      // Which foot is ahead along the body's heading.
      const Vec3 fwd = anim::yaw(c.frames[f].heading_rad()) * Vec3::UnitZ();
      const double d = (jp[kLeftAnkle] - jp[kRightAnkle]).dot(fwd);
      if (std::abs(d) > 0.15) {
        if (prev_sign != 0 && (d > 0) != (prev_sign > 0)) ++alternations;
        prev_sign = d;
      }
    }
    const double seconds = (n - 1) / c.fps;
    const double speed = path / seconds;
    INFO(file << ": speed " << speed << " m/s, " << alternations / seconds
              << " foot alternations/s, lowest joint " << lowest);
    CHECK(speed > 0.6);
    CHECK(speed < 2.2);
    CHECK(alternations / seconds > 1.2);  // ~2 steps per second in walking
    CHECK(lowest > -0.03);
    // Walks forward: the displacement over the first second is along the initial heading (+Z).
    const Vec3 d1 = c.frames[static_cast<size_t>(c.fps)].root_position_m - c.frames[0].root_position_m;
    CHECK(d1.z() > 0.4);
  }
}

// (The ankle -> toe bone is excluded: feet are deliberately re-pitched to stand flat, see retarget.hpp.)
TEST_CASE("Bandai-Namco: every clip imports, retargeted bones point where the source bones point") {
  const auto dir = test::shared_data("bandai-namco-1");
  if (dir.empty()) return;
  const BodyShape s = make_procedural_body({Sex::kFemale, 1.6, 1.0});
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".bvh") continue;
    const BvhMotion m = import_bvh(entry.path());
    const RetargetedClip c = retarget_bvh(m, s);
    const int step = test::kSanitized ? 97 : 13;
    for (int f = 0; f < m.frame_count; f += step) {
      const auto src = m.world_transforms(f);
      const auto jp = joint_positions(s, c.frames[static_cast<size_t>(f)]);
      for (auto [a, b] : {std::pair{kLeftHip, kLeftKnee},
                          {kLeftKnee, kLeftAnkle},
                          {kRightKnee, kRightAnkle},
                          {kLeftShoulder, kLeftElbow},
                          {kRightElbow, kRightWrist},
                          {kSpine1, kSpine3}}) {
        const Vec3 ds = src[static_cast<size_t>(c.map.source[static_cast<size_t>(b)])].translation -
                        src[static_cast<size_t>(c.map.source[static_cast<size_t>(a)])].translation;
        const Vec3 dt = jp[static_cast<size_t>(b)] - jp[static_cast<size_t>(a)];
        INFO(entry.path().filename().string() << " frame " << f << " bone " << joint_name(a));
        CHECK(std::acos(std::clamp(ds.normalized().dot(dt.normalized()), -1.0, 1.0)) < 0.5 * kDeg);
      }
    }
  }
}

TEST_CASE("seamless loop of a real walk: no pop at the seam, ground motion continues") {
  const auto dir = test::shared_data("bandai-namco-1");
  if (dir.empty()) return;
  const BodyShape s = make_procedural_body({Sex::kMale, 1.8, 1.0});
  RetargetedClip c = retarget_bvh(import_bvh(dir / "dataset-1_walk_normal_001.bvh"), s);
  normalize_clip_start(c.frames);
  const int first = 60, last = 60 + 66, blend = 12;  // ~2 s of steady walking
  const LoopedClip loop = make_seamless_loop(c.frames, first, last, blend);
  auto jump = [&](const Pose& a, const Pose& b) {
    const auto pa = joint_positions(s, a), pb = joint_positions(s, b);
    double w = 0;
    for (size_t j = 0; j < pa.size(); ++j) w = std::max(w, (pa[j] - pb[j]).norm());
    return w;
  };
  double typical = 0;
  for (int k = 1; k < static_cast<int>(loop.frames.size()); ++k)
    typical =
        std::max(typical, jump(loop.frames[static_cast<size_t>(k - 1)], loop.frames[static_cast<size_t>(k)]));
  const long n = static_cast<long>(loop.frames.size());
  const double seam = jump(sample_loop(loop, n - 1), sample_loop(loop, n));
  INFO("seam " << seam << " max frame step " << typical << " displacement " << loop.displacement.transpose());
  CHECK(seam <= 1.2 * typical);
  CHECK(loop.displacement.norm() > 1.0);  // it walks ~1.5 m per loop
  // Without blending the seam would pop.
  const LoopedClip raw = make_seamless_loop(c.frames, first, last - 5, 0);
  CHECK(jump(sample_loop(raw, static_cast<long>(raw.frames.size()) - 1),
             sample_loop(raw, static_cast<long>(raw.frames.size()))) > seam);
  CHECK_THROWS_AS(make_seamless_loop(c.frames, 5, 10, 8), InputError);
}

TEST_CASE("stationary crowd dancing from a BVH clip: in place, varied start times, valid crowd") {
  const auto dir = test::shared_data("bandai-namco-1");
  if (dir.empty()) return;
  AnimationSpec spec;
  spec.motion = MotionSource::clips;
  spec.dance_clips = {"dataset-1_dance-short_normal_001.bvh"};
  AnimationContext ctx;
  ctx.seed = 8;
  ctx.scenario = ScenarioKind::stationary;
  ctx.clip_directory = dir;
  CrowdTrajectories t;
  t.fps = 30;
  const size_t count = test::kSanitized ? 2 : 4;
  t.agents.resize(count);
  for (size_t i = 0; i < count; ++i) {
    t.agents[i].position_m.assign(60, Vec2(0.7 * static_cast<double>(i), 1.0));
    t.agents[i].heading_rad.assign(60, 0.2);
  }
  const CrowdAnimation crowd = animate_crowd(t, Environment{}, spec, ctx);
  CHECK_NOTHROW(validate_crowd(crowd, "clips"));
  for (size_t i = 0; i < count; ++i)
    for (const Pose& p : crowd.characters[i].frames) {
      const Vec2 d(p.root_position_m.x() - 0.7 * static_cast<double>(i), p.root_position_m.z() - 1.0);
      CHECK(d.norm() < 0.35);  // stays at its spot
    }
  // Different characters are at different points of the dance.
  CHECK(crowd.characters[0].frames[0].local_rotations[kLeftShoulder].angularDistance(
            crowd.characters[1].frames[0].local_rotations[kLeftShoulder]) > 1e-3);
  spec.dance_clips = {"missing.bvh"};
  CHECK_THROWS_AS(animate_crowd(t, Environment{}, spec, ctx), InputError);
  ctx.scenario = ScenarioKind::corridor;
  CHECK_THROWS_AS(animate_crowd(t, Environment{}, spec, ctx), InputError);
}

TEST_CASE("BVH: hostile headers are refused before any work (issue 21)") {
  // 30,000 nested JOINTs overflowed the recursive parser's stack (SIGSEGV): the depth is bounded.
  std::string deep = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 0\n";
  for (int i = 1; i < 30000; ++i) deep += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 0\n";
  for (int i = 0; i < 30000; ++i) deep += "}\n";
  deep += "MOTION\nFrames: 1\nFrame Time: 0.1\n";
  const std::string message = expect_error(deep);
  CHECK_THAT(message, Catch::Contains("bad.bvh:") && Catch::Contains("nest more than 256 levels"));
  // The bound itself is accepted.
  std::string ok = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 0\n";
  for (int i = 1; i < kMaxBvhJointDepth; ++i)
    ok += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 0\n";
  for (int i = 0; i < kMaxBvhJointDepth; ++i) ok += "}\n";
  CHECK(parse_bvh(ok + "MOTION\nFrames: 0\nFrame Time: 0.1\n", "ok.bvh").joints.size() ==
        static_cast<size_t>(kMaxBvhJointDepth));

  const std::string good = kTwoJoint;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  // A header claiming 1e8 frames on a 2-frame file: the truncation is reported, and nothing near
  // 1e8 x 9 doubles (7.2 GB) is allocated on the way (an ASan/UBSan run would abort on that).
  CHECK_THAT(expect_error(replace("Frames: 2", "Frames: 100000000")),
             Catch::Contains("bad.bvh:") && Catch::Contains("truncated MOTION section"));
  // 1000 six-channel joints x 1e8 frames would be 4.8 TB: allocating from the header threw bad_alloc.
  std::string wide =
      "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition "
      "Zrotation Xrotation Yrotation\n";
  for (int i = 1; i < 1000; ++i)
    wide += "JOINT j" + std::to_string(i) +
            "\n{\nOFFSET 0 1 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n}\n";
  CHECK_THAT(expect_error(wide + "}\nMOTION\nFrames: 100000000\nFrame Time: 0.1\n0 0 0\n"),
             Catch::Contains("bad.bvh:") && Catch::Contains("truncated MOTION section"));
  CHECK_THAT(expect_error(replace("Frame Time: 0.04", "Frame Time: 1e-9")),
             Catch::Contains("bad.bvh:18:") && Catch::Contains("Frame Time: must be between 0.0001 and 10"));
  CHECK_THAT(expect_error(replace("Frame Time: 0.04", "Frame Time: 3600")), Catch::Contains("bad.bvh:18:"));
}

TEST_CASE("BVH: a UTF-8 byte-order mark is accepted, and raw bytes in a message are escaped and cut") {
  // Was "bom.bvh:1:1: expected 'HIERARCHY', found 'HIERARCHY'" (issue 33).
  const BvhMotion plain = parse_bvh(kTwoJoint, "plain.bvh");
  const BvhMotion bom = parse_bvh(std::string("\xEF\xBB\xBF") + kTwoJoint, "bom.bvh");
  CHECK(bom.joints.size() == plain.joints.size());
  CHECK(bom.values == plain.values);
  // A binary token where a keyword belongs: its bytes are escaped and the value cut, not echoed whole.
  const std::string junk = "\x1b[2J" + std::string(5000, '\x01');
  const std::string message = expect_error(junk + "\n" + kTwoJoint);
  CHECK_THAT(message, Catch::Contains("bad.bvh:1:1:") && Catch::Contains("\\x1b[2J"));
  CHECK(message.find('\x1b') == std::string::npos);
  CHECK(message.find('\x01') == std::string::npos);
  CHECK(message.size() < 600);
}

}  // namespace test_bvh
