#include "framework/pipeline/body_model.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <mutex>

#include "framework/body/sample_mpfb2_bodies.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {
namespace {

std::shared_ptr<const Mpfb2Model> cached_model(const std::filesystem::path& dir) {
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::shared_ptr<const Mpfb2Model>> models;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = models.find(dir);
  if (it == models.end()) it = models.emplace(dir, Mpfb2Model::load(dir)).first;
  return it->second;
}

/// The wardrobe of `dir`, loaded once per process (nullptr when the folder has no wardrobe.txt).
std::shared_ptr<const Mpfb2Wardrobe> cached_wardrobe(const std::filesystem::path& dir,
                                                     const Mpfb2Model& model) {
  static std::mutex mutex;
  static std::map<std::filesystem::path, std::shared_ptr<const Mpfb2Wardrobe>> wardrobes;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = wardrobes.find(dir);
  if (it == wardrobes.end()) {
    std::shared_ptr<const Mpfb2Wardrobe> w;
    if (std::filesystem::exists(dir / "wardrobe.txt"))
      w = Mpfb2Wardrobe::load(dir, static_cast<int>(model.base().vertices.size()));
    else
      spdlog::warn("MakeHuman wardrobe '{}' has no wardrobe.txt: bodies are drawn without clothes",
                   dir.string());
    it = wardrobes.emplace(dir, std::move(w)).first;
  }
  return it->second;
}

// The spec loader fills the path (spec, else CROWDLAB_MPFB2, else the shipped assets); a spec built in
// code may leave it empty.
std::shared_ptr<const Mpfb2Model> spec_model(const AnimationSpec& spec) {
  return cached_model(spec.body_model_path.empty() ? default_mpfb2_dir()
                                                   : std::filesystem::path(spec.body_model_path));
}

}  // namespace

void load_body_model_assets(const AnimationSpec& spec) {
  if (spec.body_model != BodyModel::procedural) (void)spec_model(spec);
}

void apply_body_model(const AnimationSpec& spec, std::size_t agents, AnimationContext& context) {
  if (spec.body_model == BodyModel::procedural) return;
  const auto model = spec_model(spec);
  const auto wardrobe = cached_wardrobe(default_makehuman_dir(), *model);
  const std::vector<Mpfb2Sample> samples =
      sample_mpfb2_bodies(*model, static_cast<int>(agents), derive_seed(context.seed, "bodies"),
                          spec.female_fraction, kWorldFemaleHeight, kWorldMaleHeight, wardrobe.get());
  context.shapes.clear();
  context.meshes.clear();
  context.skin_tones.clear();
  int unreached = 0;
  for (const Mpfb2Sample& s : samples) {
    context.shapes.push_back(s.body.shape);
    context.meshes.push_back(std::make_shared<const SkinnedMesh>(s.body.mesh));
    context.skin_tones.push_back(s.skin_tone);
    unreached += s.target_reached ? 0 : 1;
  }
  if (unreached > 0)
    spdlog::info("{}: {} of {} MPFB2 bodies took the nearest reachable height", context.condition_id,
                 unreached, agents);
}

CollisionProxies resolve_collision_proxies(const AnimationSpec& spec, ScenarioKind scenario) {
  if (spec.collision_proxies != CollisionProxies::automatic) return spec.collision_proxies;
  return scenario == ScenarioKind::stationary && spec.body_model == BodyModel::mpfb2
             ? CollisionProxies::fitted
             : CollisionProxies::volume;
}

ProxyFit proxy_fit(CollisionProxies resolved) {
  switch (resolved) {
    case CollisionProxies::fitted:
      return ProxyFit::per_surface;
    case CollisionProxies::fitted_upper:
      return ProxyFit::upper_body;
    default:
      return ProxyFit::volume;
  }
}

}  // namespace crowdlab
