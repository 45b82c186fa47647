#pragma once
// Participant ids: the one rule that `crowdlab study`, the web page (export-web writes the rule into
// timeline.json, the page applies it before anything starts) and `import-web` apply, and the one
// case-clash check of a response folder.
//
// Rule: 1-64 characters of A-Z a-z 0-9 _ -, the first a letter or digit (an id never reads as a
// command-line option or a hidden file). kParticipantIdPattern is the same rule as an ECMAScript
// regular expression, for the page; a test checks that both accept the same ids.
#include <optional>
#include <string>

namespace crowdlab::study {

inline constexpr const char* kParticipantIdPattern = "^[A-Za-z0-9][A-Za-z0-9_-]{0,63}$";
inline constexpr const char* kParticipantIdRule =
    "must be 1-64 characters of A-Z a-z 0-9 _ -, starting with a letter or digit";

/// True when `participant` follows the rule above.
bool valid_participant_id(const std::string& participant);

/// Throws InputError (key --participant) naming the id and the rule when it does not follow it.
void check_participant_id(const std::string& participant);

/// The stem of a *.csv or *.json file in `dir` that equals `participant` but for ASCII case (P07 and
/// p07 are one file on a case-insensitive disk), if any; an exact match is no clash.
std::optional<std::string> case_clash(const std::string& dir, const std::string& participant);

}  // namespace crowdlab::study
