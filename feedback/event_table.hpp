#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "feedback/haptics.hpp"
#include "feedback/profile.hpp"
#include "feedback/theme.hpp"
#include "feedback/user_scores.hpp"
#include "feedback/vibra_feedback.hpp"

// The feedbackd API's rules without a bus (feedbackd 0.8.2's fbd-feedback-manager.c,
// fbd-event.c, fbd-haptic-manager.c): which events play at which level, their ids, timeouts and
// end reasons, profile changes, clients and vibscored leaving, Haptic.Vibrate patterns. It plays
// through a Haptics (vibscored, or a fake) and tells what ended through its callbacks;
// FeedbackService only translates between it and the bus. Time is given by the caller.
namespace vibscore::feedback {

// libfeedback's LfbEventEndReason, as FeedbackEnded sends it.
namespace end_reason {
inline constexpr std::uint32_t natural = 0;
inline constexpr std::uint32_t expired = 1;
inline constexpr std::uint32_t explicit_end = 2;
inline constexpr std::uint32_t not_found = 0xffffffff;  // -1
}  // namespace end_reason

// feedbackd's limits on a Haptic.Vibrate pattern (fbd-haptic-manager.c): more steps are
// dropped, a longer step is shortened and a strength outside 0..1 clamped, as feedbackd does.
inline constexpr std::size_t kMaxPatternSteps = 10;
inline constexpr std::uint32_t kMaxStepMs = 10'000;

// The settings of feedbackd's org.sigxcpu.feedbackd schema that vibscore-feedback honours.
struct FeedbackSettings {
    Profile profile = Profile::full;
    std::string haptic_usage = "touch";  // vibscored's usage for Haptic.Vibrate patterns
    // max-haptic-strength: no vibration is stronger (0..1).
    double max_haptic_strength = 1.0;
    // allow-important: the app ids whose "important" hint overrides the profile.
    // feedbackd 0.8.2's default, and vibscore-feedback's --allow-important default too.
    std::vector<std::string> allow_important = {"org.sigxcpu.FbdAlertSlider", "org.gnome.clocks"};
};

// allow-important as a command line gives it, "a,b": its app ids, in order. Empty items ("",
// ",,", a trailing comma) name none, so "" is the empty list.
std::vector<std::string> parse_app_id_list(const std::string& list);
// The inverse: the ids joined by commas ("" for none), to show a default on the command line.
std::string app_id_list(const std::vector<std::string>& app_ids);

// A TriggerFeedback call.
struct Trigger {
    std::string sender;  // the caller's unique bus name: its events end when it leaves
    std::string app_id;
    std::string event;
    std::optional<Profile> profile_hint;  // hint "profile"
    bool important = false;               // hint "important"
    std::int32_t timeout = -1;            // -1 once, 0 until ended, N > 0 for N seconds
};

// A Haptic.Vibrate step as the caller sent it.
struct HapticStep {
    double strength = 0.0;
    std::uint32_t ms = 0;
};

// An event and the score it plays (org.vibscore.Feedback1.EventScores).
struct EventScore {
    std::string event;
    std::string score;        // what it plays now: the user's choice, else the theme's
    std::string theme_score;  // the theme's registry score; "" for a pattern, or none
    bool assigned = false;    // the user chose `score`

    bool operator==(const EventScore&) const = default;
};

class EventTable {
  public:
    struct Callbacks {
        // FeedbackEnded.
        std::function<void(std::uint32_t id, std::uint32_t reason)> feedback_ended;
        // The earliest time an event's timeout runs out (CLOCK_MONOTONIC µs), each time it
        // changes; nothing when no event has one. expire() is to be called then.
        std::function<void(std::optional<std::uint64_t> deadline_us)> expiry_changed;
    };

    EventTable(Haptics& haptics, Theme theme, FeedbackSettings settings, Callbacks callbacks);

    // The id of the next event, never 0. The caller gets it before anything plays, as feedbackd
    // replies first; trigger() then plays it.
    std::uint32_t new_id();
    // Plays the event's feedback at the level the profile, its hints and the theme give, or
    // ends it at once with not-found.
    void trigger(std::uint32_t id, const Trigger& trigger, std::uint64_t now_us);
    // EndFeedback from `sender`: ends the event with reason explicit if it is the sender's;
    // another client's event, or one not playing, is left alone.
    void end(std::uint32_t id, const std::string& sender);
    // Haptic.Vibrate from `sender`: replaces that sender's pattern (an empty one only ends it).
    // Whether it plays: false below the quiet profile or when vibscored refuses it. Throws
    // std::invalid_argument naming the step for a strength that is not a number.
    bool vibrate(const std::string& sender, const std::string& app_id,
                 const std::vector<HapticStep>& pattern);

    Profile profile() const { return profile_; }
    // True when it changed. Feedback the new profile would not give ends (explicit); below
    // quiet, Haptic.Vibrate patterns end too.
    bool set_profile(Profile profile);
    const FeedbackSettings& settings() const { return settings_; }
    const Theme& theme() const { return theme_; }
    void set_max_haptic_strength(double strength);
    void set_allow_important(std::vector<std::string> app_ids);

    // The user's own scores (user_scores.hpp). An assigned event plays its score where the
    // theme's entry would play (its level and usage), or, when the theme has no entry for it,
    // at the quiet level with the usage its name gives. A score vibscored does not have plays
    // the theme's instead, with a log line. True when they changed.
    bool set_user_scores(UserScores scores);
    const UserScores& user_scores() const { return user_scores_; }
    // Every event the theme gives feedback for (quiet or full) and every assigned one, in order.
    std::vector<EventScore> event_scores() const;

    // An event's timeout ran out (the time expiry_changed gave came).
    void expire(std::uint64_t now_us);
    // vibscored's reports: a playback ended (for whatever reason); vibscored left the bus, so
    // that none of its playbacks will report an end.
    void playback_finished(std::uint64_t playback);
    void haptics_gone();
    // A client left the bus: its events end (explicit) and its pattern stops.
    void sender_left(const std::string& sender);

    // Events playing now.
    std::size_t playing() const { return events_.size(); }

  private:
    struct Event {
        std::string sender;
        Profile level = Profile::full;  // the theme level its feedback came from
        std::uint64_t playback = 0;
        std::optional<std::uint64_t> expires_us;
        std::uint32_t end_reason = end_reason::natural;
        bool ending = false;  // a stop was asked; the end follows vibscored's report
    };
    using Events = std::map<std::uint32_t, Event>;

    Profile level_for(const Trigger& trigger) const;
    // What `trigger` plays at `level`, and the theme level it counts as; nothing when it gives
    // no feedback there.
    struct Chosen {
        Haptics::Played played;
        Profile level = Profile::full;
    };
    Chosen play_for(const Trigger& trigger, Profile level);
    void end_event(Events::iterator event, std::uint32_t reason);
    void end_where(const std::function<bool(const Event&)>& which, std::uint32_t reason);
    void ended(Events::iterator event);
    void stop_pattern_of(const std::string& sender);
    // Tells expiry_changed the earliest timeout when it changed (or `always`).
    void update_expiry(bool always = false);

    Haptics& haptics_;
    Theme theme_;
    FeedbackSettings settings_;
    Callbacks callbacks_;
    Profile profile_;
    std::uint32_t next_id_ = 1;
    Events events_;
    std::map<std::string, std::uint64_t> patterns_;  // Haptic.Vibrate playbacks by sender
    UserScores user_scores_;
    std::optional<std::uint64_t> reported_expiry_;
};

}  // namespace vibscore::feedback
