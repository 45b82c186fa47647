// Stimuli: headless rendering, viewpoints, overlap mode and H.264 output.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/sha256.hpp"
#include "stimuli/mannequin_mesh.hpp"
#include "stimuli/palette.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/stimulus_entry.hpp"
#include "stimuli/synthetic_crowd.hpp"
#include "stimuli/video_encoder.hpp"
#include "tests/support/test_paths.hpp"
#include "tests/support/two_sphere_crowd.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_stimuli {

using namespace crowdlab;
using namespace crowdlab::stimuli;

namespace {

/// One renderer (EGL context + mesh cache) for the whole test binary.
/// Test meshes use a 3.5 cm grid: 3x faster to build, and plenty at 320 x 180.
MannequinOptions test_mesh_options() {
  MannequinOptions o;
  o.voxel_m = 0.035;
  return o;
}

Renderer& shared_renderer() {
  static Renderer renderer(test_mesh_options());
  return renderer;
}

RenderOptions small_options() {
  RenderOptions o;
  o.width = 320;
  o.height = 180;
  return o;
}

CrowdAnimation small_crowd(int characters, double spacing, int frames = 4) {
  SyntheticCrowdOptions co;
  co.characters = characters;
  co.spacing_m = spacing;
  co.frames = frames;
  co.stage = false;
  return make_synthetic_crowd(co);
}

/// Number of pixels that differ from the background colour by more than `tolerance` in any channel.
int non_background_pixels(const BgrImage& img, const Rgb& bg, int tolerance = 6) {
  int count = 0;
  for (size_t p = 0; p + 2 < img.bgr.size(); p += 3) {
    const int b = img.bgr[p], g = img.bgr[p + 1], r = img.bgr[p + 2];
    if (std::abs(r - std::lround(bg[0] * 255)) > tolerance ||
        std::abs(g - std::lround(bg[1] * 255)) > tolerance ||
        std::abs(b - std::lround(bg[2] * 255)) > tolerance)
      ++count;
  }
  return count;
}

}  // namespace

TEST_CASE("mannequin mesh is a closed, well-skinned surface around the capsules", "[stimuli]") {
  for (Sex sex : {Sex::kFemale, Sex::kMale}) {
    BodyParams params{sex, sex == Sex::kFemale ? 1.6 : 1.85, sex == Sex::kFemale ? 0.9 : 1.2};
    const BodyShape shape = make_procedural_body(params);
    MannequinOptions options;
    options.voxel_m = test::kSanitized ? 0.04 : 0.025;
    const MannequinMesh mesh = build_mannequin_mesh(shape, options);
    REQUIRE(mesh.indices.size() % 3 == 0);
    REQUIRE(mesh.vertices.size() > 500);
    // Closed 2-manifold: every undirected edge is used by exactly two triangles, once in each direction.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (size_t t = 0; t < mesh.indices.size(); t += 3)
      for (int e = 0; e < 3; ++e) directed[{mesh.indices[t + e], mesh.indices[t + (e + 1) % 3]}]++;
    int bad = 0;
    for (const auto& [edge, count] : directed) {
      const auto reverse = directed.find({edge.second, edge.first});
      if (count != 1 || reverse == directed.end() || reverse->second != 1) ++bad;
    }
    CHECK(bad == 0);
    // Vertices lie on the body: within a voxel of the capsule union's surface (or inside the blend).
    const WorldCapsules caps = world_capsules(shape, Pose::rest(shape));
    int far = 0;
    for (const MannequinVertex& v : mesh.vertices) {
      const Vec3 p(v.position[0], v.position[1], v.position[2]);
      double d = 1e9;
      for (const Capsule& c : caps) {
        const SegmentClosestPoints s = segment_closest_points(p, p, c.a, c.b);
        d = std::min(d, s.distance_m - c.radius_m);
      }
      if (d > 1.01 * options.voxel_m || d < -options.blend_m - options.voxel_m) ++far;
      int sum = 0;
      for (int k = 0; k < 4; ++k) {
        sum += v.weights[static_cast<size_t>(k)];
        REQUIRE(v.bones[static_cast<size_t>(k)] < kJointCount);
      }
      REQUIRE(sum == 255);
      REQUIRE(std::abs(Vec3(v.normal[0], v.normal[1], v.normal[2]).norm() - 1.0) < 1e-3);
    }
    CHECK(far == 0);
    // Outward orientation: the signed volume (divergence theorem) is positive and near the capsules'.
    double volume = 0.0;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      const auto& a = mesh.vertices[mesh.indices[t]].position;
      const auto& b = mesh.vertices[mesh.indices[t + 1]].position;
      const auto& c = mesh.vertices[mesh.indices[t + 2]].position;
      volume += Vec3(a[0], a[1], a[2]).dot(Vec3(b[0], b[1], b[2]).cross(Vec3(c[0], c[1], c[2]))) / 6.0;
    }
    CHECK(volume > 0.7 * 0.6 * shape.capsule_volume_sum_m3());
    CHECK(volume < 1.3 * shape.capsule_volume_sum_m3());
  }
}

TEST_CASE("at least 12 distinct palettes", "[stimuli]") {
  REQUIRE(palette_count() >= 12);
  std::set<std::array<float, 6>> distinct;
  for (int i = 0; i < palette_count(); ++i)
    distinct.insert({palette(i).shirt[0], palette(i).shirt[1], palette(i).shirt[2], palette(i).trousers[0],
                     palette(i).skin[0], palette(i).hair[0]});
  CHECK(static_cast<int>(distinct.size()) == palette_count());
  CHECK(&palette(-1) == &palette(palette_count() - 1));
}

TEST_CASE("camera projects its target to the image centre and rejects points behind it", "[stimuli]") {
  Camera cam;
  cam.eye = Vec3(3, 2, 5);
  cam.target = Vec3(-1, 0.5, 0);
  cam.width = 640;
  cam.height = 360;
  const auto c = cam.project(cam.target);
  REQUIRE(c);
  CHECK(c->x() == Approx(320.0).margin(1e-6));
  CHECK(c->y() == Approx(180.0).margin(1e-6));
  CHECK_FALSE(cam.project(cam.eye + (cam.eye - cam.target)));
  // A point above the target appears above the centre (smaller y, image rows go down).
  CHECK(cam.project(cam.target + Vec3(0, 0.5, 0))->y() < 180.0);
}

TEST_CASE("viewpoints: presets, overrides and errors", "[stimuli]") {
  const CrowdAnimation crowd = small_crowd(4, 0.8);
  for (const std::string& name : viewpoint_names())
    CHECK_NOTHROW(Viewpoint(*find_viewpoint(name), crowd, 320, 180));
  CHECK_FALSE(find_viewpoint("V9"));
  ViewpointOverrides overrides{{ViewpointId::V1, {1, 2, 3, 0, 1, 0, 50}}};
  const Camera cam = Viewpoint(ViewpointId::V1, crowd, 320, 180, overrides).at(0);
  CHECK(cam.eye.isApprox(Vec3(1, 2, 3)));
  CHECK(cam.fov_y_deg == 50.0);
  // The spec loader checks placements (camera_placement_problem); an unchecked one is a programming error.
  overrides[ViewpointId::V1] = {1, 2, 3, 1, 2, 3, 50};
  CHECK_THROWS_AS(Viewpoint(ViewpointId::V1, crowd, 320, 180, overrides), std::logic_error);
  CHECK(Viewpoint::placed("mine", {1, 2, 3, 0, 1, 0, 50}, 320, 180).name() == "mine");
  // Framing: every root projects inside the image for every preset, for a small and a long crowd.
  SyntheticCrowdOptions long_crowd;
  long_crowd.characters = 12;
  long_crowd.spacing_m = 3.0;
  long_crowd.frames = 2;
  for (const CrowdAnimation& c : {crowd, make_synthetic_crowd(long_crowd)})
    for (const char* name : {"V1", "V2", "V3", "V4", "pair"}) {
      const Camera cc = Viewpoint(*find_viewpoint(name), c, 320, 180).at(0);
      for (const CharacterAnimation& ch : c.characters) {
        const auto p = cc.project(ch.frames[0].root_position_m);
        REQUIRE(p);
        CHECK(p->x() > 0);
        CHECK(p->x() < 320);
        CHECK(p->y() > 0);
        CHECK(p->y() < 180);
      }
    }
}

TEST_CASE("frames are not blank and characters appear where the camera model predicts", "[stimuli]") {
  CrowdAnimation crowd = small_crowd(6, 0.9);
  crowd.environment.ground_plane = false;  // only characters differ from the background
  RenderOptions options = small_options();
  for (const std::string& name : viewpoint_names()) {
    INFO("viewpoint " << name);
    const Camera cam = Viewpoint(*find_viewpoint(name), crowd, options.width, options.height).at(1);
    const BgrImage img = render_frame(shared_renderer(), crowd, options, cam, 1);
    const int covered = non_background_pixels(img, options.scene.background);
    CHECK(covered > 0.01 * options.width * options.height);
    int checked = 0, hit = 0;
    for (const CharacterAnimation& c : crowd.characters) {
      // Centre of the head capsule, and the mid-torso, in the world.
      const BoneTransforms bones = forward_kinematics(c.shape, c.frames[1]);
      for (int joint : {static_cast<int>(kHead), static_cast<int>(kSpine2)}) {
        const Capsule cap =
            c.shape.capsules[static_cast<size_t>(joint)].transformed(bones[static_cast<size_t>(joint)]);
        const auto px = cam.project(0.5 * (cap.a + cap.b));
        if (!px || px->x() < 0 || px->y() < 0 || px->x() >= img.width || px->y() >= img.height) continue;
        const size_t at = 3 * (static_cast<size_t>(px->y()) * static_cast<size_t>(img.width) +
                               static_cast<size_t>(px->x()));
        BgrImage one{1, 1, {img.bgr[at], img.bgr[at + 1], img.bgr[at + 2]}};
        ++checked;
        hit += non_background_pixels(one, options.scene.background) == 1;
      }
    }
    CHECK(checked >= 6);
    CHECK(hit == checked);
  }
  // An empty view (camera looking at the sky) is all background.
  Camera sky;
  sky.eye = Vec3(0, 50, 0);
  sky.target = Vec3(0, 100, 1);
  sky.width = options.width;
  sky.height = options.height;
  CHECK(non_background_pixels(render_frame(shared_renderer(), crowd, options, sky, 0),
                              options.scene.background) == 0);
}

TEST_CASE("overlap mode: more red pixels on an interpenetrating crowd than on a separated one", "[stimuli]") {
  RenderOptions options = small_options();
  options.scene.overlap = true;
  const CrowdAnimation separated = small_crowd(9, 1.2, 2);
  const CrowdAnimation overlapping = small_crowd(9, 0.32, 2);
  double red_separated = -1, red_overlapping = -1;
  const BgrImage a = render_frame(shared_renderer(), separated, options,
                                  Viewpoint(ViewpointId::V2, separated, 320, 180).at(0), 0, &red_separated);
  const BgrImage b =
      render_frame(shared_renderer(), overlapping, options,
                   Viewpoint(ViewpointId::V2, overlapping, 320, 180).at(0), 0, &red_overlapping);
  CHECK(red_separated == 0.0);
  CHECK(red_overlapping > 0.005);
  // Red pixels are actually red in the image.
  int red_in_image = 0;
  for (size_t p = 0; p + 2 < b.bgr.size(); p += 3)
    red_in_image += b.bgr[p + 2] > 120 && b.bgr[p + 1] < 40 && b.bgr[p] < 40;
  CHECK(red_in_image > 0.5 * red_overlapping * 320 * 180);
  // With overlap mode off nothing is flagged.
  options.scene.overlap = false;
  double red_off = -1;
  render_frame(shared_renderer(), overlapping, options,
               Viewpoint(ViewpointId::V2, overlapping, 320, 180).at(0), 0, &red_off);
  CHECK(red_off == 0.0);
}

TEST_CASE("overlap mode paints rendered meshes inside each other, where the capsules do not meet",
          "[stimuli]") {
  // Spheres of 1.2 m around pelvises 2 m apart: the rendered meshes overlap by 40 cm, the capsules are
  // 25 cm apart, so the capsule test painted nothing here (tests/support/two_sphere_crowd.hpp).
  RenderOptions options = small_options();
  options.scene.overlap = true;
  const CrowdAnimation overlapping = test::two_sphere_crowd(2.0, 1.2);
  const CrowdAnimation apart = test::two_sphere_crowd(2.6, 1.2);
  Camera cam;
  cam.eye = Vec3(1.0, 1.0, -4.0);
  cam.target = Vec3(1.0, 1.0, 0.0);
  cam.width = options.width;
  cam.height = options.height;
  double red_overlapping = -1, red_apart = -1;
  const BgrImage b = render_frame(shared_renderer(), overlapping, options, cam, 0, &red_overlapping);
  render_frame(shared_renderer(), apart, options, cam, 0, &red_apart);
  CHECK(red_apart == 0.0);
  // The common lens seen from the front lies within 30 cm behind the visible surface over its middle
  // ~0.19 m (|x - 1| < 0.095) and up to ~1.2 m tall: at 4 m (62 px/m) some 700 px, 1.2 % of the image.
  CHECK(red_overlapping > 0.002);
  int red_in_image = 0;
  for (size_t p = 0; p + 2 < b.bgr.size(); p += 3)
    red_in_image += b.bgr[p + 2] > 120 && b.bgr[p + 1] < 40 && b.bgr[p] < 40;
  CHECK(red_in_image > 0.5 * red_overlapping * 320 * 180);
}

TEST_CASE("re-rendering gives bit-identical frames, with 1 or many TBB threads and a fresh renderer",
          "[stimuli]") {
  const CrowdAnimation crowd = small_crowd(5, 0.6);
  RenderOptions options = small_options();
  options.scene.overlap = true;
  const Camera cam = Viewpoint(ViewpointId::V3, crowd, 320, 180).at(2);
  const BgrImage first = render_frame(shared_renderer(), crowd, options, cam, 2);
  const BgrImage again = render_frame(shared_renderer(), crowd, options, cam, 2);
  CHECK(first.bgr == again.bgr);
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  Renderer fresh(test_mesh_options());
  const BgrImage other = render_frame(fresh, crowd, options, cam, 2);
  size_t differing = 0;
  for (size_t i = 0; i < first.bgr.size(); ++i) differing += first.bgr[i] != other.bgr[i];
  CHECK(differing == 0);
}

TEST_CASE("render_clip writes a decodable H.264 MP4 with the right frame count, rate and size", "[stimuli]") {
  const CrowdAnimation crowd = small_crowd(4, 0.8, 12);
  RenderOptions options = small_options();
  options.scene.overlap = true;
  const auto dir = test::scratch_dir("stimuli_clip");
  const std::string path = (dir / "clip.mp4").string();
  options.frames_png_dir = (dir / "png").string();
  const RenderResult r = render_clip(shared_renderer(), crowd, options, ViewpointId::V1, path);
  CHECK(r.frames == 12);
  CHECK(r.duration_s == Approx(12.0 / 30.0));
  CHECK(r.red_fraction.size() == 12);
  CHECK(r.render_ms.size() == 12);
  CHECK(std::filesystem::exists(dir / "png" / "frame_00011.png"));

  AVFormatContext* fmt = nullptr;
  REQUIRE(avformat_open_input(&fmt, path.c_str(), nullptr, nullptr) == 0);
  REQUIRE(avformat_find_stream_info(fmt, nullptr) >= 0);
  const int stream = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  REQUIRE(stream >= 0);
  AVStream* st = fmt->streams[stream];
  CHECK(st->codecpar->codec_id == AV_CODEC_ID_H264);
  CHECK(st->codecpar->width == 320);
  CHECK(st->codecpar->height == 180);
  CHECK(st->codecpar->format == AV_PIX_FMT_YUV420P);
  CHECK(av_q2d(st->avg_frame_rate) == Approx(30.0));
  const AVCodec* codec = avcodec_find_decoder(st->codecpar->codec_id);
  AVCodecContext* dec = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(dec, st->codecpar);
  REQUIRE(avcodec_open2(dec, codec, nullptr) == 0);
  AVPacket* pkt = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  int decoded = 0;
  std::vector<std::int64_t> pts;
  auto receive = [&] {
    while (avcodec_receive_frame(dec, frame) == 0) {
      ++decoded;
      pts.push_back(frame->best_effort_timestamp);
    }
  };
  while (av_read_frame(fmt, pkt) >= 0) {
    if (pkt->stream_index == stream) {
      avcodec_send_packet(dec, pkt);
      receive();
    }
    av_packet_unref(pkt);
  }
  avcodec_send_packet(dec, nullptr);
  receive();
  CHECK(decoded == 12);
  // Presentation times step by exactly one frame duration.
  for (size_t i = 1; i < pts.size(); ++i)
    CHECK(av_rescale_q(pts[i] - pts[i - 1], st->time_base, AVRational{1, 30000}) == 1000);
  av_frame_free(&frame);
  av_packet_free(&pkt);
  avcodec_free_context(&dec);
  avformat_close_input(&fmt);
  // faststart: the moov atom precedes mdat.
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  CHECK(bytes.find("moov") < bytes.find("mdat"));
  // Its manifest row.
  const StimulusEntry entry = make_stimulus_entry("c1_V1", {{"viewpoint", "V1"}}, path, "clip.mp4", r);
  CHECK(entry.frames == 12);
  CHECK(entry.width == 320);
  CHECK(entry.height == 180);
  CHECK(entry.duration_s == Approx(0.4));
  CHECK(entry.sha256 == sha256_hex(bytes));
}

TEST_CASE("odd or invalid video sizes are rejected with a clear error", "[stimuli]") {
  const CrowdAnimation crowd = small_crowd(1, 1.0, 2);
  RenderOptions options = small_options();
  options.width = 321;
  const auto dir = test::scratch_dir("stimuli_odd");
  try {
    render_clip(shared_renderer(), crowd, options, ViewpointId::V1, (dir / "odd.mp4").string());
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("even") != std::string::npos);
  }
  CHECK_THROWS_AS(validate_video_settings({320, 181, 30.0, 18, "veryfast"}), InputError);
  CHECK_THROWS_AS(validate_video_settings({320, 180, 30.0, 60, "veryfast"}), InputError);
  CHECK_THROWS_AS(validate_video_settings({320, 180, 0.0, 18, "veryfast"}), InputError);
  CHECK_FALSE(std::filesystem::exists(dir / "odd.mp4"));
}

TEST_CASE("background colour parsing", "[stimuli]") {
  const Rgb c = parse_hex_colour("#ff8000", "render.background");
  CHECK(c[0] == 1.0f);
  CHECK(c[1] == Approx(128 / 255.0));
  CHECK(c[2] == 0.0f);
  CHECK_THROWS_AS(parse_hex_colour("#ff80", "render.background"), InputError);
  CHECK_THROWS_AS(parse_hex_colour("#gg8000", "render.background"), InputError);
}

TEST_CASE("a wall between the camera and the crowd is cut away, walls elsewhere are drawn", "[stimuli]") {
  CrowdAnimation crowd = small_crowd(1, 1.0, 2);
  crowd.environment.ground_plane = false;
  const Vec3 root = crowd.characters[0].frames[0].root_position_m;
  Box near_wall;  // between the camera (in front, +Z) and the character
  near_wall.center_m = Vec3(root.x(), 1.0, root.z() + 1.0);
  near_wall.half_extents_m = Vec3(3.0, 1.0, 0.05);
  Box side_wall;  // beside the character, not in the line of sight
  side_wall.center_m = Vec3(root.x() + 1.5, 0.5, root.z());
  side_wall.half_extents_m = Vec3(0.05, 0.5, 1.0);
  crowd.environment.boxes = {near_wall, side_wall};
  RenderOptions options = small_options();
  Camera cam;
  cam.eye = Vec3(root.x(), 1.4, root.z() + 4.0);
  cam.target = Vec3(root.x() + 0.5, 1.0, root.z());
  cam.width = options.width;
  cam.height = options.height;
  const BgrImage img = render_frame(shared_renderer(), crowd, options, cam, 0);
  auto colour_at = [&](const Vec3& world) {
    const auto px = cam.project(world);
    REQUIRE(px);
    const size_t at =
        3 * (static_cast<size_t>(px->y()) * static_cast<size_t>(img.width) + static_cast<size_t>(px->x()));
    return std::array<int, 3>{img.bgr[at + 2], img.bgr[at + 1], img.bgr[at]};
  };
  const Rgb env = options.scene.environment;
  auto is_environment = [&](const std::array<int, 3>& c) {
    // Lit environment colour: a scaled copy of the base colour (equal channel ratios, not background).
    return non_background_pixels(BgrImage{1,
                                          1,
                                          {static_cast<std::uint8_t>(c[2]), static_cast<std::uint8_t>(c[1]),
                                           static_cast<std::uint8_t>(c[0])}},
                                 options.scene.background) == 1 &&
           std::abs(static_cast<double>(c[0] * env[2] - c[2] * env[0])) < 0.08 * 255;
  };
  // The character's chest is visible through the cut-away near wall ...
  const std::array<int, 3> chest = colour_at(root + Vec3(0, 0.35, 0));
  CHECK_FALSE(is_environment(chest));
  CHECK(non_background_pixels(
            BgrImage{1,
                     1,
                     {static_cast<std::uint8_t>(chest[2]), static_cast<std::uint8_t>(chest[1]),
                      static_cast<std::uint8_t>(chest[0])}},
            options.scene.background) == 1);
  // ... and the side wall is drawn.
  CHECK(is_environment(colour_at(side_wall.center_m + Vec3(-0.05, 0.2, 0.5))));
}

}  // namespace test_stimuli
