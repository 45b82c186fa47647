#pragma once
// StudyQuestion: one question as a participant sees it, resolved from the spec's protocol with the
// protocol defaults filled in, plus reverse coding.
//
// Defaults when the spec lists no questions (the papers' protocols):
//   likert : seed 000 §4.4.1, six statements Q1..Q6 on a 6-point scale, 1 "I strongly disagree" ..
//            6 "I fully agree"; Q2, Q4, Q6 are reverse-keyed (the negative item of each pair).
//   2afc   : seed 001 §3.1.5, "Did the characters go through each other?" (yes/no, keys y/n), then
//            "How natural was the interaction?" 1 (not very natural) .. 7 (very natural).
//   rating : seed 001 §4.2.2, "How often did you see collisions between characters?" 1 (never) ..
//            7 (very often) and "How natural was the way the characters moved in the crowd?"
//            1 (not very natural) .. 7 (very natural); neither is reverse-keyed (seed 001 analyses
//            them as two separate dependent variables, §4.2.3).
// Reverse coding (seed 000 §4.4.3): Q̄ = (k + 1) - Q for a k-point item (7 - Q on 6 points).
// A yes/no answer is recorded as 1 = yes, 0 = no; it is never reverse-coded.
#include <string>
#include <vector>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::study {

enum class QuestionKind { scale, yesno };

struct StudyQuestion {
  std::string id;
  std::string text;
  QuestionKind kind = QuestionKind::scale;
  int points = 6;                         ///< k for a scale (2..11); 2 for yes/no
  std::string low_label;                  ///< label under the lowest point ("" = none)
  std::string high_label;                 ///< label under the highest point
  std::vector<std::string> point_labels;  ///< one per point when the spec gives them all
  bool reverse = false;

  /// Lowest and highest valid raw response (1..k for scales, 0..1 for yes/no).
  int min_response() const { return kind == QuestionKind::yesno ? 0 : 1; }
  int max_response() const { return kind == QuestionKind::yesno ? 1 : points; }
  bool valid(int raw) const { return raw >= min_response() && raw <= max_response(); }
};

/// The questions asked on every trial, in order. Throws InputError on a
/// scale with fewer than 2 or more than 11 points, or duplicate question ids.
std::vector<StudyQuestion> resolve_questions(const ProtocolSpec& protocol);

/// Reverse-coded value of a raw answer: (k + 1) - raw for reverse-keyed scale items, raw otherwise.
int reverse_coded(const StudyQuestion& question, int raw);

}  // namespace crowdlab::study
