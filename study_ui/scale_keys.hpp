#pragma once
// scale_keys: answering scale questions from the keyboard. Digits answer the first unanswered scale
// question. Scales of 10 or 11 points (kMaxScalePoints) need two digits for 10 and 11: a 1 answers 1
// at once but stays open, and a following digit d makes that answer 10 + d when the scale has that
// point (otherwise d answers the next question as usual); a 0 waits for its second digit, so 01 .. 09
// also work. Any other key or a click closes an open digit.
#include <optional>
#include <utility>
#include <vector>

#include "study_ui/study_question.hpp"
#include "study_ui/trial_screen.hpp"

namespace crowdlab::study {

struct DigitEntry {
  int question = -1;  ///< the question whose first digit is still open, or -1
  int first = -1;     ///< that digit (0 or 1)
};

/// Applies digit d (0..9): returns the {question, value} to answer, or nullopt; updates `entry`.
std::optional<std::pair<int, int>> enter_digit(DigitEntry& entry, const TrialScreenState& state,
                                               const std::vector<StudyQuestion>& questions, int d);

}  // namespace crowdlab::study
