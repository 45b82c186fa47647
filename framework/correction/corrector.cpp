#include "framework/correction/corrector.hpp"

#include "framework/correction/corrector_step.hpp"

namespace crowdlab {

Corrector::Corrector(std::vector<BodyShape> shapes, CorrectorParams params, Environment env, double fps)
    : model_(make_corrector_model(std::move(shapes), params, env, fps)),
      state_(make_corrector_state(model_)) {}

std::vector<Pose> Corrector::step(const std::vector<Pose>& targets) {
  return corrector_step(model_, state_, targets);
}

}  // namespace crowdlab
