#include "study_ui/participant_id.hpp"

#include <filesystem>

#include "framework/core/error.hpp"

namespace crowdlab::study {
namespace fs = std::filesystem;
namespace {

bool alnum(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
}

std::string ascii_lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

}  // namespace

bool valid_participant_id(const std::string& participant) {
  bool ok = !participant.empty() && participant.size() <= 64 && alnum(participant.front());
  for (char c : participant) ok = ok && (alnum(c) || c == '_' || c == '-');
  return ok;
}

void check_participant_id(const std::string& participant) {
  if (!valid_participant_id(participant))
    throw InputError(SourceLocation{"", 0, 0, "--participant"},
                     "participant id '" + participant + "' " + kParticipantIdRule);
}

std::optional<std::string> case_clash(const std::string& dir, const std::string& participant) {
  if (!fs::is_directory(dir)) return std::nullopt;
  const std::string folded = ascii_lower(participant);
  for (const auto& entry : fs::directory_iterator(dir)) {
    const fs::path name = entry.path().filename();
    const std::string ext = name.extension().string();
    const std::string stem = name.stem().string();
    if ((ext == ".csv" || ext == ".json") && stem != participant && ascii_lower(stem) == folded) return stem;
  }
  return std::nullopt;
}

}  // namespace crowdlab::study
