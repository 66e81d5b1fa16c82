#include "feedback/feedback_service.hpp"

#include <algorithm>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "common/log.hpp"
#include "common/monotonic_clock.hpp"
#include "common/quoted_text.hpp"
#include "dbus/feedback1_names.hpp"
#include "dbus/name_owner_watch.hpp"
#include "dbus/sdbus_compat.hpp"

namespace vibscore::feedback {

namespace {

using feedback1::errors::kBusy;
using feedback1::errors::kFailed;
using feedback1::errors::kInvalidArgs;
using feedback1::errors::kLimitExceeded;

// The generated adaptors serve the interfaces the names header spells: checked where both meet.
static_assert(std::string_view(org::sigxcpu::Feedback_adaptor::INTERFACE_NAME) ==
              feedback1::kFeedbackdInterface);
static_assert(std::string_view(org::sigxcpu::Feedback::Haptic_adaptor::INTERFACE_NAME) ==
              feedback1::kHapticInterface);
static_assert(std::string_view(org::vibscore::Feedback1_adaptor::INTERFACE_NAME) ==
              feedback1::kInterface);

sdbus::Error invalid_args(const std::string& message) {
    return dbus::bus_error(kInvalidArgs, message);
}

// TriggerFeedback's hints: "profile" (s) and "important" (b); others ("sound-file") have no
// effect on vibration.
void read_hints(const std::map<std::string, sdbus::Variant>& hints, Trigger& trigger) {
    if (const auto hint = hints.find("profile"); hint != hints.end()) {
        const std::string held = dbus::variant_signature(hint->second);
        if (held != "s") {
            throw invalid_args("hint \"profile\" must be a string (s), not " + held);
        }
        const auto name = hint->second.get<std::string>();
        trigger.profile_hint = parse_profile(name);
        if (!trigger.profile_hint) {
            throw invalid_args("hint \"profile\": unknown profile \"" + name + "\" (expected " +
                               std::string(kProfileNames) + ")");
        }
    }
    if (const auto hint = hints.find("important"); hint != hints.end()) {
        const std::string held = dbus::variant_signature(hint->second);
        if (held != "b") {
            throw invalid_args("hint \"important\" must be a boolean (b), not " + held);
        }
        trigger.important = hint->second.get<bool>();
    }
}

}  // namespace

FeedbackService::FeedbackService(sdbus::IConnection& session_bus, sdbus::IConnection& system_bus,
                                 daemon::EventLoop& loop, Theme theme, FeedbackSettings settings,
                                 std::optional<std::filesystem::path> user_scores)
    : AdaptorInterfaces(session_bus, dbus::object_path(feedback1::kObjectPath)),
      haptics_(system_bus, {[this](std::uint64_t playback, const std::string&) {
                                table_.playback_finished(playback);
                            },
                            [this] { table_.haptics_gone(); }}),
      table_(haptics_, std::move(theme), std::move(settings),
             {[this](std::uint32_t id, std::uint32_t reason) { emitFeedbackEnded(id, reason); },
              [this](std::optional<std::uint64_t> deadline_us) {
                  if (deadline_us) {
                      expiry_.arm(*deadline_us);
                  } else {
                      expiry_.disarm();
                  }
              }}),
      expiry_(loop, [this] { table_.expire(monotonic_now_us()); }),
      user_scores_(std::move(user_scores)) {
    vanish_watch_ = dbus::watch_connections_leaving(
        session_bus, [this](const std::string& name) { table_.sender_left(name); });
    if (user_scores_) {
        try {
            make_user_directory(user_scores_->parent_path());
            user_scores_watch_ =
                std::make_unique<FileWatch>(loop, *user_scores_, [this] { load_user_scores(); });
        } catch (const std::exception& error) {
            log::warning(std::string(error.what()) + ": changes to " + user_scores_->string() +
                         " are not seen until a restart");
        }
        // What a store killed half-way left (SIGKILL, a crash): no one else writes them.
        try {
            for (const auto& stale : remove_stale_temporaries_of(*user_scores_)) {
                log::info("removed " + stale.string() + ", left by a store that was interrupted");
            }
        } catch (const std::exception& error) {
            log::warning(error.what());
        }
        load_user_scores();
        writer_ = std::make_unique<UserScoresWriter>(loop, *user_scores_);
    }
    registerAdaptor();
}

FeedbackService::~FeedbackService() {
    unregisterAdaptor();
}

void FeedbackService::load_user_scores() {
    try {
        std::vector<Diagnostic> warnings;
        auto scores = read_user_scores(*user_scores_, warnings);
        for (const auto& warning : warnings) {
            log::warning(format(warning));
        }
        const auto count = scores.size();
        if (table_.set_user_scores(std::move(scores))) {
            log::info(std::to_string(count) + " of your own scores for events, from " +
                      user_scores_->string());
            emitEventScoresChanged();
        }
    } catch (const std::exception& error) {
        if (user_scores_read_) {
            log::warning(std::string(error.what()) + " (the scores read before stay)");
        } else {
            // At start nothing was read before: say it so that it is not taken for "none".
            log::error(std::string(error.what()) +
                       ": none of your own scores for events are used until this file is "
                       "mended, and it is never written over (AssignScore refuses)");
        }
        return;
    }
    user_scores_read_ = true;
}

std::vector<sdbus::Struct<std::string, std::string, std::string, bool>>
FeedbackService::EventScores() {
    std::vector<sdbus::Struct<std::string, std::string, std::string, bool>> list;
    for (const auto& event : table_.event_scores()) {
        list.emplace_back(event.event, event.score, event.theme_score, event.assigned);
    }
    return list;
}

void FeedbackService::check_assignment(const std::string& event, const std::string& score) const {
    try {
        check_event_and_score(event, score);
    } catch (const std::invalid_argument& error) {
        throw invalid_args(error.what());
    }
    // Giving back takes any name the file holds, so that a name read past can be taken out.
    if (!score.empty() && !table_.theme().events().contains(event) && !is_event_name(event)) {
        throw invalid_args("event " + quoted_text(event) + " is not in the theme \"" +
                           table_.theme().name + "\" and is not an event name (" +
                           std::string(kEventNameRule) + ")");
    }
}

void FeedbackService::AssignScore(sdbus::Result<>&& result, std::string event, std::string score) {
    try {
        check_assignment(event, score);
    } catch (const sdbus::Error& error) {
        result.returnError(error);
        return;
    }
    if (!writer_) {
        result.returnError(dbus::bus_error(kFailed,
                                           "vibscore-feedback has no config directory (neither "
                                           "XDG_CONFIG_HOME nor HOME is set)"));
        return;
    }
    // std::function copies what it holds; a reply can be sent once only.
    auto reply = std::make_shared<sdbus::Result<>>(std::move(result));
    const std::string caller = sender();
    const bool queued = writer_->submit(
        event, score, [this, reply, event, score, caller](std::exception_ptr error) {
            assigned(*reply, event, score, caller, error);
        });
    if (!queued) {
        reply->returnError(dbus::bus_error(
            kBusy, std::to_string(UserScoresWriter::kMaxWaiting) +
                       " choices wait to be stored already: try again when they are"));
    }
}

void FeedbackService::assigned(sdbus::Result<>& result, const std::string& event,
                               const std::string& score, const std::string& caller,
                               std::exception_ptr error) {
    if (error) {
        try {
            std::rethrow_exception(error);
        } catch (const std::invalid_argument& refused) {
            result.returnError(invalid_args(refused.what()));
        } catch (const AssignmentLimit& limit) {
            result.returnError(dbus::bus_error(kLimitExceeded, limit.what()));
        } catch (const std::exception& failed) {
            result.returnError(dbus::bus_error(
                kFailed,
                "cannot store the score for " + quoted_text(event) + ": " + failed.what()));
        }
        return;
    }
    log::info("event " + quoted_text(event) + " plays " +
              (score.empty() ? std::string("the theme's score") : quoted_text(score)) +
              " from now on (" + caller + ")");
    // Before the reply: the caller's next trigger plays its choice.
    load_user_scores();
    result.returnResults();
}

std::string FeedbackService::sender() const {
    return dbus::with_current_message(
        getObject(), [](const sdbus::Message& message) { return dbus::sender_of(message); });
}

void FeedbackService::TriggerFeedback(sdbus::Result<std::uint32_t>&& result, std::string app_id,
                                      std::string event,
                                      std::map<std::string, sdbus::Variant> hints,
                                      std::int32_t timeout) {
    // feedbackd's own checks, answered as feedbackd answers them.
    if (app_id.empty()) {
        result.returnError(invalid_args("Invalid app id " + app_id));
        return;
    }
    if (event.empty()) {
        result.returnError(invalid_args("Invalid event " + event));
        return;
    }
    Trigger trigger{sender(), std::move(app_id),    std::move(event), std::nullopt,
                    false,    std::max(timeout, -1)};
    try {
        read_hints(hints, trigger);
    } catch (const sdbus::Error& error) {
        result.returnError(error);
        return;
    }
    // The caller has its id before anything plays, as with feedbackd.
    const std::uint32_t id = table_.new_id();
    result.returnResults(id);
    table_.trigger(id, trigger, monotonic_now_us());
}

void FeedbackService::EndFeedback(const std::uint32_t& id) {
    table_.end(id, sender());
}

void FeedbackService::Profile(const std::string& value) {
    const auto profile = parse_profile(value);
    if (!profile) {
        throw invalid_args("unknown profile \"" + value + "\" (expected " +
                           std::string(kProfileNames) + ")");
    }
    if (table_.set_profile(*profile)) {
        dbus::emit_properties_changed(getObject(), org::sigxcpu::Feedback_adaptor::INTERFACE_NAME,
                                      {"Profile"});
    }
}

bool FeedbackService::Vibrate(const std::string& app_id,
                              const std::vector<sdbus::Struct<double, std::uint32_t>>& pattern) {
    std::vector<HapticStep> steps;
    steps.reserve(pattern.size());
    for (const auto& step : pattern) {
        steps.push_back({step.get<0>(), step.get<1>()});
    }
    try {
        return table_.vibrate(sender(), app_id, steps);
    } catch (const std::invalid_argument& error) {
        throw invalid_args(error.what());
    }
}

}  // namespace vibscore::feedback
