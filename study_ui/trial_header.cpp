// trial_header (declared in presenter.hpp): what the participant reads above the video. Practice
// trials are counted apart, so "Trial 1 of 40" starts after the practice, and N is the test trials.
#include "study_ui/presenter.hpp"

namespace crowdlab::study {

std::string trial_header(const TrialRequest& r) {
  const bool practice = r.trial != nullptr && r.trial->practice;
  return std::string(practice ? "Practice trial " : "Trial ") + std::to_string(r.number) + " of " +
         std::to_string(r.count);
}

}  // namespace crowdlab::study
