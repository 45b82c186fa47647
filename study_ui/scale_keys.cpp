#include "study_ui/scale_keys.hpp"

namespace crowdlab::study {

std::optional<std::pair<int, int>> enter_digit(DigitEntry& entry, const TrialScreenState& state,
                                               const std::vector<StudyQuestion>& questions, int d) {
  if (entry.question >= 0) {  // the second digit of an open answer
    const DigitEntry open = entry;
    entry = {};
    const int value = open.first * 10 + d;
    const int points = questions[static_cast<size_t>(open.question)].points;
    if (value >= (open.first == 1 ? 10 : 1) && value <= points) return std::make_pair(open.question, value);
  }
  const int q = state.first_unanswered(questions, QuestionKind::scale);
  if (q < 0) return std::nullopt;
  const int points = questions[static_cast<size_t>(q)].points;
  if (points >= 10 && d <= 1) {  // may be the first of two digits
    entry = {q, d};
    if (d == 1) return std::make_pair(q, 1);
    return std::nullopt;
  }
  if (d >= 1 && d <= points) return std::make_pair(q, d);
  return std::nullopt;
}

}  // namespace crowdlab::study
