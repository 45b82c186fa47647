#pragma once
// The fixed texts of a study session's screens, shared by the native session (run_session) and the
// web study (export_web), so that both show participants the same words.
namespace crowdlab::study::texts {

inline constexpr const char* kPracticeTitle = "Practice";
inline constexpr const char* kPracticeIntro =
    // Worded for any number of practice trials: the demo has one (issue 21 item 10d).
    "First some practice, to get used to the task.\n"
    "Your answers during the practice are not analysed.\n\nPress any key to start.";
inline constexpr const char* kAfterPractice =
    "The practice is over. The experiment starts now.\n\nPress any key.";
inline constexpr const char* kBlockIntro = "Press any key to continue.";
inline constexpr const char* kMainPartTitle = "Main part";
inline constexpr const char* kPartTitlePrefix = "Part ";  ///< + block number
inline constexpr const char* kBreakTitle = "Break";
inline constexpr const char* kFinishedTitle = "Thank you";
inline constexpr const char* kFinished =
    "The session is complete. Thank you for taking part!\n\nPress any key to close.";

}  // namespace crowdlab::study::texts
