#pragma once
// The fixed texts of a study session's screens. session_plan puts them into the plan that the native
// window and the web page both show, so both show participants the same words. A screen's body says
// what the screen is about; its hint line (at the bottom) says which key moves on, once.
namespace crowdlab::study::texts {

inline constexpr const char* kInstructionsTitle = "Instructions";
inline constexpr const char* kConsentTitle = "Consent";
inline constexpr const char* kPracticeTitle = "Practice";
inline constexpr const char* kPracticeIntro =
    // Worded for any number of practice trials: the demo has one (issue 21 item 10d).
    "First some practice, to get used to the task.\n"
    "Your answers during the practice are not analysed.";
inline constexpr const char* kAfterPractice = "The practice is over. The experiment starts now.";
inline constexpr const char* kBlockIntro = "The next part of the experiment starts now.";
inline constexpr const char* kMainPartTitle = "Main part";
inline constexpr const char* kPartTitlePrefix = "Part ";  ///< + block number
inline constexpr const char* kBreakTitle = "Break";
inline constexpr const char* kFinishedTitle = "Thank you";
inline constexpr const char* kFinished = "The session is complete. Thank you for taking part!";

inline constexpr const char* kContinueHint = "Press any key (or click) to continue";
inline constexpr const char* kConsentHint = "Press Y if you agree to take part, N if you do not";
inline constexpr const char* kCloseHint = "Press any key (or click) to close";
/// The Next button's label on a trial screen while its answers are locked (protocol.min_view_ms).
inline constexpr const char* kLockedLabel = "Watch the clip";

}  // namespace crowdlab::study::texts
