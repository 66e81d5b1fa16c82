#pragma once

#include <string_view>

// The names of the object vibscore-feedback serves on the session bus, as
// feedback/org.sigxcpu.Feedback.xml and feedback/org.vibscore.Feedback1.xml document them: the
// one spelling of each, for vibscore-feedback that owns them and the client (`vibscore assign`,
// the editor's "use for ...") that calls it. feedbackd's API keeps feedbackd's names, so a
// program written for feedbackd finds vibscore-feedback in its place; vibscore's own interface
// sits on the same object.
namespace vibscore::feedback1 {

inline constexpr const char* kBusName = "org.sigxcpu.Feedback";
inline constexpr const char* kObjectPath = "/org/sigxcpu/Feedback";
// feedbackd's interfaces (TriggerFeedback, Profile; the Haptic patterns).
inline constexpr const char* kFeedbackdInterface = "org.sigxcpu.Feedback";
inline constexpr const char* kHapticInterface = "org.sigxcpu.Feedback.Haptic";
// vibscore's own: the user's score per event (EventScores, AssignScore).
inline constexpr const char* kInterface = "org.vibscore.Feedback1";

// The named errors vibscore-feedback sends; its own begin with kErrorPrefix.
namespace errors {
inline constexpr std::string_view kErrorPrefix = "org.vibscore.Feedback1.Error.";
inline constexpr const char* kLimitExceeded = "org.vibscore.Feedback1.Error.LimitExceeded";
inline constexpr const char* kBusy = "org.vibscore.Feedback1.Error.Busy";

// Not ours: a malformed argument, and the generic failure when none of the names above fits.
inline constexpr const char* kInvalidArgs = "org.freedesktop.DBus.Error.InvalidArgs";
inline constexpr const char* kFailed = "org.freedesktop.DBus.Error.Failed";
}  // namespace errors

}  // namespace vibscore::feedback1
