// vibscore-feedback: the feedbackd API (org.sigxcpu.Feedback) on the session bus, played through
// vibscored. This file only wires: the command line, the theme, the two buses and the loop.
#include <CLI/CLI.hpp>

#include <sdbus-c++/sdbus-c++.h>

#include <csignal>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "common/event_loop.hpp"
#include "common/log.hpp"
#include "common/usage.hpp"
#include "config.h"
#include "dbus/feedback1_names.hpp"
#include "dbus/sdbus_compat.hpp"
#include "feedback/feedback_service.hpp"
#include "feedback/feedbackd_theme.hpp"
#include "feedback/theme.hpp"
#include "feedback/user_scores.hpp"
#include "json/build_tree.hpp"

using namespace vibscore;
using namespace vibscore::feedback;

namespace {

// The command line's defaults are FeedbackSettings' (feedbackd's), written once there.
struct Options {
    std::string theme;
    std::string profile = std::string(to_string(FeedbackSettings().profile));
    std::string haptic_usage = FeedbackSettings().haptic_usage;
    double max_haptic_strength = FeedbackSettings().max_haptic_strength;
    std::string allow_important = app_id_list(FeedbackSettings().allow_important);
    bool verbose = false;
};

int serve(const Options& options) {
    const Theme theme = load_theme(options.theme, ThemeSearch::from_environment());
    for (const auto& warning : theme.warnings) {
        log::warning(format(warning));
    }
    log::info("theme \"" + theme.name + "\" (" + options.theme + "), " +
              std::to_string(theme.events().size()) + " events");
    daemon::EventLoop loop;
    // The session bus DBUS_SESSION_BUS_ADDRESS names, as feedbackd serves; vibscored's bus.
    auto session_bus = sdbus::createSessionBusConnection();
    auto system_bus = sdbus::createSystemBusConnection();

    FeedbackSettings settings;
    settings.profile = *parse_profile(options.profile);
    settings.haptic_usage = options.haptic_usage;
    settings.max_haptic_strength = options.max_haptic_strength;
    settings.allow_important = parse_app_id_list(options.allow_important);
    std::optional<std::filesystem::path> user_scores;
    try {
        user_scores = user_scores_path();
    } catch (const std::exception& error) {
        log::warning(std::string(error.what()) + ": events play the theme's scores only");
    }
    FeedbackService service(*session_bus, *system_bus, loop, theme, std::move(settings),
                            user_scores);
    dbus::request_name(*session_bus, feedback1::kBusName);
    daemon::BusLoopBinding session_binding(loop, *session_bus);
    daemon::BusLoopBinding system_binding(loop, *system_bus);

    auto on_term = loop.on_signal(SIGTERM, [&] { loop.exit(0); });
    auto on_int = loop.on_signal(SIGINT, [&] { loop.exit(0); });
    log::info("vibscore-feedback " VIBSCORE_VERSION " ready on " +
              std::string(feedback1::kBusName) + ", profile " + options.profile);
    const int code = loop.run();
    dbus::release_name(*session_bus, feedback1::kBusName);
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    options.theme = default_feedback_theme(data_locations()).string();
    CLI::App app(
        "The feedbackd API (org.sigxcpu.Feedback) on the session bus, played through "
        "vibscored. Run with no arguments it serves the bus DBUS_SESSION_BUS_ADDRESS "
        "names. docs/feedbackd.md explains the themes.",
        "vibscore-feedback");
    app.add_option("--theme", options.theme,
                   "theme file: vibscore's format or feedbackd's theme JSON (default: "
                   "$FEEDBACK_THEME; from a build tree, its checkout's "
                   "feedback/themes/default.json; else " VIBSCORE_FEEDBACK_THEME ")");
    app.add_option("--profile", options.profile, "profile to start with")
        ->check(CLI::IsMember({"full", "quiet", "silent"}))
        ->capture_default_str();
    app.add_option("--haptic-usage", options.haptic_usage,
                   "vibscored usage of org.sigxcpu.Feedback.Haptic patterns")
        ->check([](const std::string& usage) {
            return daemon::parse_usage(usage) ? std::string()
                                              : "expected " + std::string(daemon::usage_names());
        })
        ->capture_default_str();
    app.add_option("--max-haptic-strength", options.max_haptic_strength,
                   "no vibration is stronger than this, 0..1 (feedbackd's max-haptic-strength)")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--allow-important", options.allow_important,
                   "app ids, comma-separated, whose \"important\" hint overrides the profile "
                   "(feedbackd's allow-important; empty: none)")
        ->capture_default_str();
    app.add_flag("-v,--verbose", options.verbose, "log every event");
    app.set_version_flag("--version", VIBSCORE_VERSION);
    CLI11_PARSE(app, argc, argv);
    log::set_verbose(options.verbose);
    try {
        return serve(options);
    } catch (const std::exception& error) {
        log::error(error.what());
        return 1;
    }
}
