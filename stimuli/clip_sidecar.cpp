#include "stimuli/clip_sidecar.hpp"

#include <string>

namespace crowdlab::stimuli {
namespace {

nlohmann::json vec_json(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

nlohmann::json pose_json(const Camera& camera) {
  return {{"eye", vec_json(camera.eye)}, {"target", vec_json(camera.target)}, {"up", vec_json(camera.up())}};
}

}  // namespace

nlohmann::json camera_json(const Camera& camera) {
  nlohmann::json j = pose_json(camera);
  j["fov_y_deg"] = camera.fov_y_deg;
  j["near_m"] = camera.near_m;
  j["far_m"] = camera.far_m;
  j["width"] = camera.width;
  j["height"] = camera.height;
  return j;
}

nlohmann::json clip_sidecar(const Viewpoint& view, int frames, const CrowdAnimation& crowd) {
  nlohmann::json j;
  j["format"] = "crowdlab-clip/1";
  j["viewpoint"] = view.name();
  j["frames"] = frames;
  j["fps"] = crowd.meta.fps;
  j["camera"] = camera_json(view.at(0));
  j["camera"]["moves"] = view.moves();
  if (view.moves()) {
    nlohmann::json per_frame = nlohmann::json::array();
    for (int f = 0; f < frames; ++f) per_frame.push_back(pose_json(view.at(f)));
    j["camera_per_frame"] = std::move(per_frame);
  }
  nlohmann::json characters = nlohmann::json::array();
  for (const CharacterAnimation& c : crowd.characters)
    characters.push_back({{"name", c.name},
                          {"sex", std::string(to_string(c.shape.params.sex))},
                          {"height_m", c.shape.params.height_m}});
  j["characters"] = std::move(characters);
  return j;
}

std::filesystem::path clip_sidecar_path(const std::filesystem::path& clip) {
  std::filesystem::path p = clip;
  return p.replace_extension(".json");
}

}  // namespace crowdlab::stimuli
