// vibscore-feedback: the feedbackd API (org.sigxcpu.Feedback) on the session bus, played through
// vibscored. This file only wires: the command line, the theme, the two buses and the loop.
#include <CLI/CLI.hpp>

#include <sdbus-c++/sdbus-c++.h>

#include <csignal>
#include <cstdlib>
#include <iostream>

#include "config.h"
#include "daemon/event_loop.hpp"
#include "daemon/log.hpp"
#include "daemon/usage.hpp"
#include "dbus/sdbus_compat.hpp"
#include "feedback/feedback_service.hpp"
#include "feedback/theme.hpp"

using namespace vibscore;
using namespace vibscore::feedback;

namespace {

constexpr const char* kBusName = "org.sigxcpu.Feedback";

struct Options {
    std::string theme;
    std::string profile = "full";
    std::string haptic_usage = "touch";
    bool verbose = false;
};

int serve(const Options& options) {
    const Theme theme = load_theme(options.theme);
    log::info("theme \"" + theme.name + "\" (" + options.theme + "), " +
              std::to_string(theme.events().size()) + " events");
    daemon::EventLoop loop;
    // The session bus DBUS_SESSION_BUS_ADDRESS names, as feedbackd serves; vibscored's bus.
    auto session_bus = sdbus::createSessionBusConnection();
    auto system_bus = sdbus::createSystemBusConnection();

    FeedbackService service(*session_bus, *system_bus, loop, theme,
                            {*parse_profile(options.profile), options.haptic_usage});
    dbus::request_name(*session_bus, kBusName);
    daemon::BusLoopBinding session_binding(loop, *session_bus);
    daemon::BusLoopBinding system_binding(loop, *system_bus);

    auto on_term = loop.on_signal(SIGTERM, [&] { loop.exit(0); });
    auto on_int = loop.on_signal(SIGINT, [&] { loop.exit(0); });
    log::info("vibscore-feedback " VIBSCORE_VERSION " ready on " + std::string(kBusName) +
              ", profile " + options.profile);
    const int code = loop.run();
    dbus::release_name(*session_bus, kBusName);
    return code;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    const char* theme_variable = std::getenv("FEEDBACK_THEME");
    options.theme = theme_variable != nullptr && *theme_variable != '\0' ? theme_variable
                                                                         : VIBSCORE_FEEDBACK_THEME;
    CLI::App app(
        "The feedbackd API (org.sigxcpu.Feedback) on the session bus, played through "
        "vibscored. Run with no arguments it serves the bus DBUS_SESSION_BUS_ADDRESS "
        "names. docs/feedbackd.md explains the themes.",
        "vibscore-feedback");
    app.add_option("--theme", options.theme,
                   "theme file: vibscore's format or feedbackd's theme JSON (default: "
                   "$FEEDBACK_THEME, else " VIBSCORE_FEEDBACK_THEME ")");
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
