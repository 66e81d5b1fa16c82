#pragma once

#include <signal.h>

#include <sdbus-c++/sdbus-c++.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dbus/sdbus_compat.hpp"
#include "feedback-proxy.h"
#include "tests/support/daemon_fixture.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

// The feedbackd API's side of the tests and benchmarks: a user's session bus, vibscore-feedback
// or the real feedbackd serving it, and the clients that call it (fbcli, a typed client).
namespace vibscore::testing {

// A private session bus, as a phone's user session has, with the session's own config
// directory (XDG_CONFIG_HOME of everything run on it, activated services included), so that
// nothing touches the real user's. Only the services a test names can be started on demand:
// never the installed feedbackd by accident.
class SessionBus {
  public:
    // `activatable`: bus name and the command line that serves it, started on the first call.
    explicit SessionBus(const std::vector<std::pair<std::string, std::string>>& activatable = {});
    ~SessionBus();
    SessionBus(const SessionBus&) = delete;
    SessionBus& operator=(const SessionBus&) = delete;

    const std::string& address() const { return address_; }
    // The session's XDG_CONFIG_HOME (vibscore-feedback's scores file is under it).
    std::filesystem::path config_home() const { return dir_.path() / "config"; }
    // busctl on this bus.
    CommandResult busctl(const std::vector<std::string>& args) const;
    // Whether `name` has an owner within `timeout`.
    bool wait_for_owner(const std::string& name,
                        std::chrono::milliseconds timeout = std::chrono::seconds(10)) const;
    // argv run with this bus as its session bus and its config directory.
    std::vector<std::string> on_this_bus(std::vector<std::string> argv) const;

  private:
    TempDir dir_;
    std::string address_;
    std::unique_ptr<Process> bus_;
};

// The org.sigxcpu.Feedback name, object and interfaces.
inline constexpr const char* kFeedbackName = "org.sigxcpu.Feedback";
inline constexpr const char* kFeedbackPath = "/org/sigxcpu/Feedback";

// A FeedbackEnded signal, when this client saw it.
struct EndedFeedback {
    std::uint32_t id = 0;
    std::uint32_t reason = 0;
    std::chrono::steady_clock::time_point at;
};

// A typed client of org.sigxcpu.Feedback and .Haptic, recording every FeedbackEnded and every
// announced change of Profile.
class FeedbackClient
    : public sdbus::ProxyInterfaces<org::sigxcpu::Feedback_proxy,
                                    org::sigxcpu::Feedback::Haptic_proxy, sdbus::Properties_proxy> {
  public:
    explicit FeedbackClient(const SessionBus& bus);
    ~FeedbackClient();

    std::optional<EndedFeedback> wait_ended(
        std::uint32_t id, std::chrono::milliseconds timeout = std::chrono::seconds(10));
    std::vector<std::string> profile_changes();

  private:
    void onFeedbackEnded(const std::uint32_t& id, const std::uint32_t& reason) override;
    void onPropertiesChanged(const dbus::InterfaceName& interface,
                             const dbus::ChangedProperties& changed,
                             const std::vector<dbus::PropertyName>& invalidated) override;

    std::mutex mutex_;
    std::vector<EndedFeedback> ended_;
    std::vector<std::string> profile_changes_;
};

// A program that serves org.sigxcpu.Feedback on a session bus (vibscore-feedback, or the real
// feedbackd), up and owning the name when the constructor returns.
class FeedbackServer {
  public:
    FeedbackServer(const SessionBus& bus, const std::vector<std::string>& argv);
    ~FeedbackServer();
    FeedbackServer(const FeedbackServer&) = delete;
    FeedbackServer& operator=(const FeedbackServer&) = delete;

    std::string log() const { return read_file(dir_.path() / "server.log"); }
    bool running() { return process_->running(); }

  private:
    TempDir dir_;
    std::unique_ptr<Process> process_;
};

// vibscore-feedback from the build tree ($VIBSCORE_FEEDBACK) with these arguments.
std::vector<std::string> vibscore_feedback(const std::vector<std::string>& args);
// Debian's feedbackd, settings in memory (no dconf), as a phone's session starts it; with a
// `root`, the feedbackd of that Debian root (another release's), chrooted there, which must
// see /dev, /proc, /sys, /run and /tmp (the session bus's socket).
std::vector<std::string> real_feedbackd(const std::filesystem::path& root = "/");

// fbcli, libfeedback's own command line client, as an application runs: its standard input is
// held open, since it ends the feedback at a newline or at the end of its input.
class Fbcli {
  public:
    Fbcli(const SessionBus& bus, const std::vector<std::string>& args);
    // The exit status, or nothing while it still runs after `timeout`.
    std::optional<int> wait(std::chrono::milliseconds timeout = std::chrono::seconds(10));
    // The user presses Return: fbcli ends the feedback.
    void press_return() { process_->write_stdin("\n"); }
    void kill() { process_->signal(SIGKILL); }
    std::string output() const { return read_file(dir_.path() / "fbcli.log"); }
    std::chrono::steady_clock::time_point started() const { return started_; }

  private:
    TempDir dir_;
    std::chrono::steady_clock::time_point started_;
    std::unique_ptr<Process> process_;
};

}  // namespace vibscore::testing
