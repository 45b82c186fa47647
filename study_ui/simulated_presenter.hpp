#pragma once
// SimulatedPresenter: a simulated observer in place of a participant (--simulate, simulate-study).
// Screens are acknowledged at once; each trial's answers come from simulate_answers() with a stream
// derived from the observer seed and the stimulus id, so an interrupted and resumed simulated session
// gives the same answers as an uninterrupted one.
#include "study_ui/presenter.hpp"
#include "study_ui/simulated_observer.hpp"

namespace crowdlab::study {

class SimulatedPresenter final : public Presenter {
 public:
  SimulatedPresenter(ObserverModel model, std::uint64_t observer_seed)
      : model_(std::move(model)), observer_(draw_observer(model_, observer_seed)) {}
  ScreenInfo screen() const override { return {0, 0, "simulated"}; }
  ScreenReply show_screen(const PlanScreen&) override { return ScreenReply::proceed; }
  TrialOutcome run_trial(const TrialRequest& request) override {
    Rng rng(derive_seed(observer_.seed, "trial:" + request.trial->stimulus.id));
    TrialOutcome out;
    out.answers = simulate_answers(model_, observer_, request.trial->stimulus, *request.questions, rng);
    const std::string now = iso8601_utc_now();
    for (Answer& a : out.answers) a.timestamp_utc = now;
    return out;
  }
  const Observer& observer() const { return observer_; }

 private:
  ObserverModel model_;
  Observer observer_;
};

}  // namespace crowdlab::study
