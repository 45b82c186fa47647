#pragma once
// The closed choices of a spec and of its conditions, as enums with their spelling in YAML and in file
// names: the scenario kind, the method a condition shows, the body model, the motion source and the
// passing side. The spec loader parses each once (framework/spec/load_experiment_spec.cpp) and later
// stages compare enums, never text (issue 22.3).
//   ScenarioKind  stationary | corridor | pair_crossing | flow_a | flow_b | manifold
//   CrowdMethod   baseline (the animation stage's output) | ours (after the collision correction,
//                 seed 000 §3.4)
//   BodyModel     procedural (capsule mannequins) | mpfb2 (MakeHuman/MPFB2 CC0 bodies)
//   MotionSource  procedural (synthesised walks and dances) | clips (the spec's BVH/glTF clips)
//   PassingSide   left | right | alternate (pair_crossing, seed 001 §3.1.4; alternate by repetition)
//   CrowdModel    orca | social | cost | none (crowd.model: the 2D navigation model,
//                 framework/crowd/make_navigation_model.hpp)
//   ProtocolType  likert (seed 000 §4.4.1) | 2afc | rating (seed 001 §3.2, §4.2.3)  (protocol.type)
//   BlockOrder    random | fixed | latin_square  (protocol.block_order; study_ui/build_trial_list.hpp)
//   InterTrialScreen  blank | fixation  (protocol.inter_trial.screen)
//   CollisionProxies  auto | volume | fitted | fitted_upper  (animation.collision_proxies: the capsules
//                 the correction separates and the capsule metrics measure;
//                 framework/body/fit_crowd_proxies.hpp)
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace crowdlab {

enum class ScenarioKind { stationary, corridor, pair_crossing, flow_a, flow_b, manifold };
enum class CrowdMethod { baseline, corrected };
enum class BodyModel { procedural, mpfb2 };
enum class MotionSource { procedural, clips };
enum class PassingSide { left, right, alternate };
enum class CrowdModel { orca, social, cost, none };
enum class ProtocolType { likert, two_afc, rating };
enum class BlockOrder { random, fixed, latin_square };
enum class InterTrialScreen { blank, fixation };
enum class CollisionProxies { automatic, volume, fitted, fitted_upper };

inline constexpr std::size_t kCrowdMethodCount = 2;
inline std::size_t index_of(CrowdMethod method) {
  return static_cast<std::size_t>(method);
}

/// Each enum's spellings, in declaration order (specialised below).
template <class E>
struct KindNames;
template <>
struct KindNames<ScenarioKind> {
  static constexpr std::array<std::pair<ScenarioKind, std::string_view>, 6> names{
      {{ScenarioKind::stationary, "stationary"},
       {ScenarioKind::corridor, "corridor"},
       {ScenarioKind::pair_crossing, "pair_crossing"},
       {ScenarioKind::flow_a, "flow_a"},
       {ScenarioKind::flow_b, "flow_b"},
       {ScenarioKind::manifold, "manifold"}}};
};
template <>
struct KindNames<CrowdMethod> {
  static constexpr std::array<std::pair<CrowdMethod, std::string_view>, 2> names{
      {{CrowdMethod::baseline, "baseline"}, {CrowdMethod::corrected, "ours"}}};
};
template <>
struct KindNames<BodyModel> {
  static constexpr std::array<std::pair<BodyModel, std::string_view>, 2> names{
      {{BodyModel::procedural, "procedural"}, {BodyModel::mpfb2, "mpfb2"}}};
};
template <>
struct KindNames<MotionSource> {
  static constexpr std::array<std::pair<MotionSource, std::string_view>, 2> names{
      {{MotionSource::procedural, "procedural"}, {MotionSource::clips, "clips"}}};
};
template <>
struct KindNames<PassingSide> {
  static constexpr std::array<std::pair<PassingSide, std::string_view>, 3> names{
      {{PassingSide::left, "left"}, {PassingSide::right, "right"}, {PassingSide::alternate, "alternate"}}};
};

template <>
struct KindNames<CrowdModel> {
  static constexpr std::array<std::pair<CrowdModel, std::string_view>, 4> names{
      {{CrowdModel::orca, "orca"},
       {CrowdModel::social, "social"},
       {CrowdModel::cost, "cost"},
       {CrowdModel::none, "none"}}};
};

template <>
struct KindNames<ProtocolType> {
  static constexpr std::array<std::pair<ProtocolType, std::string_view>, 3> names{
      {{ProtocolType::likert, "likert"}, {ProtocolType::two_afc, "2afc"}, {ProtocolType::rating, "rating"}}};
};
template <>
struct KindNames<BlockOrder> {
  static constexpr std::array<std::pair<BlockOrder, std::string_view>, 3> names{
      {{BlockOrder::random, "random"},
       {BlockOrder::fixed, "fixed"},
       {BlockOrder::latin_square, "latin_square"}}};
};
template <>
struct KindNames<InterTrialScreen> {
  static constexpr std::array<std::pair<InterTrialScreen, std::string_view>, 2> names{
      {{InterTrialScreen::blank, "blank"}, {InterTrialScreen::fixation, "fixation"}}};
};

template <>
struct KindNames<CollisionProxies> {
  static constexpr std::array<std::pair<CollisionProxies, std::string_view>, 4> names{
      {{CollisionProxies::automatic, "auto"},
       {CollisionProxies::volume, "volume"},
       {CollisionProxies::fitted, "fitted"},
       {CollisionProxies::fitted_upper, "fitted_upper"}}};
};

/// The spelling of `value` ("corridor", "ours", ...).
template <class E>
std::string_view kind_name(E value) {
  for (const auto& [v, name] : KindNames<E>::names)
    if (v == value) return name;
  return {};
}

/// The value spelled `text`, or nullopt.
template <class E>
std::optional<E> parse_kind(std::string_view text) {
  for (const auto& [v, name] : KindNames<E>::names)
    if (name == text) return v;
  return std::nullopt;
}

/// Every spelling of E, in declaration order (for validation messages).
template <class E>
std::vector<std::string> kind_names() {
  std::vector<std::string> out;
  for (const auto& entry : KindNames<E>::names) out.emplace_back(entry.second);
  return out;
}

/// True for the area scenarios, whose crowd size is density x area (stationary, corridor).
inline bool is_area_scenario(ScenarioKind kind) {
  return kind == ScenarioKind::stationary || kind == ScenarioKind::corridor;
}

}  // namespace crowdlab
