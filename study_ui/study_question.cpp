#include "study_ui/study_question.hpp"

#include <set>

#include "framework/core/error.hpp"

namespace crowdlab::study {
namespace {

StudyQuestion scale_question(std::string id, std::string text, int points, std::string low, std::string high,
                             bool reverse) {
  StudyQuestion q;
  q.id = std::move(id);
  q.text = std::move(text);
  q.points = points;
  q.low_label = std::move(low);
  q.high_label = std::move(high);
  q.reverse = reverse;
  return q;
}

std::vector<StudyQuestion> default_questions(ProtocolType type, int points, const std::string& low,
                                             const std::string& high) {
  if (type == ProtocolType::likert) {
    // seed 000 §4.4.1: the six assertions, positive/negative per pair.
    const char* texts[6] = {"Contacts made by characters between them seem natural to me",
                            "Character bodies overlap, it is not physically realistic to me",
                            "Characters seem to make contact and sometimes push one another",
                            "Characters move as if they were alone, their motion ignore neighbors",
                            "A crowd moving like this one could exist in the real life",
                            "I feel this crowd as a whole does not move in a natural way"};
    std::vector<StudyQuestion> qs;
    for (int i = 0; i < 6; ++i)
      qs.push_back(scale_question("Q" + std::to_string(i + 1), texts[i], points, low, high, i % 2 == 1));
    return qs;
  }
  if (type == ProtocolType::two_afc) {
    StudyQuestion yn;
    yn.id = "collision";
    yn.text = "Did the characters go through each other?";
    yn.kind = QuestionKind::yesno;
    yn.points = 2;
    yn.low_label = "no";
    yn.high_label = "yes";
    return {yn, scale_question("naturalness", "How natural was the interaction?", 7, "not very natural",
                               "very natural", false)};
  }
  // ProtocolType::rating
  return {scale_question("collisions", "How often did you see collisions between characters?", 7, "never",
                         "very often", false),
          scale_question("naturalness", "How natural was the way the characters moved in the crowd?", 7,
                         "not very natural", "very natural", false)};
}

}  // namespace

std::vector<StudyQuestion> resolve_questions(const ProtocolSpec& protocol) {
  const ProtocolType type = protocol.type;
  int points = protocol.scale_points;
  if (type != ProtocolType::likert && points == 6 && protocol.scale_labels.empty())
    points = 7;                                                     // seed 001 uses 1..7
  std::string low = "I strongly disagree", high = "I fully agree";  // seed 000 §4.4.1 anchors
  if (type != ProtocolType::likert) low = "not very natural", high = "very natural";
  if (protocol.scale_labels.size() >= 2)
    low = protocol.scale_labels.front(), high = protocol.scale_labels.back();

  std::vector<StudyQuestion> out;
  if (protocol.questions.empty()) {
    out = default_questions(type, points, low, high);
  } else {
    for (const QuestionSpec& qs : protocol.questions) {
      StudyQuestion q;
      q.id = qs.id;
      q.text = qs.text;
      q.reverse = qs.reverse;
      if (qs.kind == "yesno") {
        q.kind = QuestionKind::yesno;
        q.points = 2;
        q.low_label = "no";
        q.high_label = "yes";
      } else if (qs.kind == "scale") {
        q.points = qs.points > 0 ? qs.points : points;
        q.low_label = low;
        q.high_label = high;
        if (static_cast<int>(qs.labels.size()) == q.points) {
          q.point_labels = qs.labels;
          q.low_label = qs.labels.front();
          q.high_label = qs.labels.back();
        } else if (qs.labels.size() == 2) {
          q.low_label = qs.labels[0];
          q.high_label = qs.labels[1];
        }
      } else {
        throw InputError(SourceLocation{"", 0, 0, "protocol.questions." + qs.id + ".kind"},
                         "unknown question kind '" + qs.kind + "' (scale | yesno)");
      }
      out.push_back(std::move(q));
    }
  }
  std::set<std::string> ids;
  for (const StudyQuestion& q : out) {
    if (q.id.empty())
      throw InputError(SourceLocation{"", 0, 0, "protocol.questions"}, "a question has no id");
    if (!ids.insert(q.id).second)
      throw InputError(SourceLocation{"", 0, 0, "protocol.questions"},
                       "duplicate question id '" + q.id + "'");
    if (q.kind == QuestionKind::scale && (q.points < 2 || q.points > 11))
      throw InputError(SourceLocation{"", 0, 0, "protocol.questions." + q.id + ".points"},
                       "a scale needs 2..11 points, got " + std::to_string(q.points));
    if (q.kind == QuestionKind::yesno && q.reverse)
      throw InputError(SourceLocation{"", 0, 0, "protocol.questions." + q.id + ".reverse"},
                       "a yes/no question cannot be reverse-keyed");
  }
  return out;
}

int reverse_coded(const StudyQuestion& question, int raw) {
  if (question.kind == QuestionKind::scale && question.reverse) return question.points + 1 - raw;
  return raw;
}

}  // namespace crowdlab::study
