#include "tests/support/feedback_fixture.hpp"

#include <signal.h>

#include <fstream>
#include <thread>

namespace vibscore::testing {

namespace {

// A session bus like the one dbus-daemon --session gives, but whose only services are the
// test's: /usr/share/dbus-1/services (where feedbackd's activation file is) is not searched.
std::string session_bus_config(const std::filesystem::path& service_dir) {
    return "<!DOCTYPE busconfig PUBLIC \"-//freedesktop//DTD D-BUS Bus Configuration 1.0//EN\"\n"
           " \"http://www.freedesktop.org/standards/dbus/1.0/busconfig.dtd\">\n"
           "<busconfig>\n  <type>session</type>\n  <listen>unix:tmpdir=/tmp</listen>\n"
           "  <auth>EXTERNAL</auth>\n  <servicedir>" +
           service_dir.string() +
           "</servicedir>\n"
           "  <policy context=\"default\">\n    <allow send_destination=\"*\" "
           "eavesdrop=\"true\"/>\n"
           "    <allow eavesdrop=\"true\"/>\n    <allow own=\"*\"/>\n  </policy>\n</busconfig>\n";
}

}  // namespace

SessionBus::SessionBus(const std::vector<std::pair<std::string, std::string>>& activatable) {
    const auto services = dir_.path() / "services";
    std::filesystem::create_directories(services);
    for (const auto& [name, command] : activatable) {
        dir_.write("services/" + name + ".service",
                   "[D-BUS Service]\nName=" + name + "\nExec=" + command + "\n");
    }
    const auto config = dir_.write("session.conf", session_bus_config(services));
    const auto socket = dir_.path() / "bus";
    address_ = "unix:path=" + socket.string();
    // Services it starts inherit its environment: the session's config directory.
    bus_ = std::make_unique<Process>(
        std::vector<std::string>{"/usr/bin/env", "XDG_CONFIG_HOME=" + config_home().string(),
                                 "/usr/bin/dbus-daemon", "--config-file=" + config.string(),
                                 "--address=" + address_, "--nofork", "--nopidfile"},
        dir_.path() / "bus.log");
    wait_until_bus_accepts(*bus_, socket, dir_.path() / "bus.log");
}

SessionBus::~SessionBus() = default;

std::vector<std::string> SessionBus::on_this_bus(std::vector<std::string> argv) const {
    argv.insert(argv.begin(), {"/usr/bin/env", "DBUS_SESSION_BUS_ADDRESS=" + address_,
                               "XDG_CONFIG_HOME=" + config_home().string()});
    return argv;
}

CommandResult SessionBus::busctl(const std::vector<std::string>& args) const {
    std::vector<std::string> argv{"/usr/bin/busctl", "--address=" + address_};
    argv.insert(argv.end(), args.begin(), args.end());
    return run_command(argv);
}

bool SessionBus::wait_for_owner(const std::string& name, std::chrono::milliseconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
        const auto names = busctl({"list", "--no-pager", "--no-legend", "--acquired"});
        if (names.out.find(name + " ") != std::string::npos) {
            return true;
        }
        if (std::chrono::steady_clock::now() >= deadline) {
            return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

// The proxy owns its connection and serves it from its own thread, where signals arrive.
FeedbackClient::FeedbackClient(const SessionBus& bus)
    : ProxyInterfaces(sdbus::createSessionBusConnectionWithAddress(bus.address()),
                      dbus::service_name(kFeedbackName), dbus::object_path(kFeedbackPath)) {
    registerProxy();
}

FeedbackClient::~FeedbackClient() {
    unregisterProxy();
}

void FeedbackClient::onFeedbackEnded(const std::uint32_t& id, const std::uint32_t& reason) {
    std::lock_guard lock(mutex_);
    ended_.push_back({id, reason, std::chrono::steady_clock::now()});
}

void FeedbackClient::onPropertiesChanged(const dbus::InterfaceName& interface,
                                         const dbus::ChangedProperties& changed,
                                         const std::vector<dbus::PropertyName>&) {
    const auto profile = changed.find(dbus::PropertyName("Profile"));
    if (interface == "org.sigxcpu.Feedback" && profile != changed.end()) {
        std::lock_guard lock(mutex_);
        profile_changes_.push_back(profile->second.get<std::string>());
    }
}

std::vector<std::string> FeedbackClient::profile_changes() {
    std::lock_guard lock(mutex_);
    return profile_changes_;
}

std::optional<EndedFeedback> FeedbackClient::wait_ended(std::uint32_t id,
                                                        std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        {
            std::lock_guard lock(mutex_);
            for (const auto& ended : ended_) {
                if (ended.id == id) {
                    return ended;
                }
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return std::nullopt;
}

FeedbackServer::FeedbackServer(const SessionBus& bus, const std::vector<std::string>& argv) {
    process_ = std::make_unique<Process>(bus.on_this_bus(argv), dir_.path() / "server.log");
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < deadline) {
        if (!process_->running()) {
            throw std::runtime_error(argv.at(0) + " exited at start:\n" + log());
        }
        if (bus.wait_for_owner(kFeedbackName, std::chrono::milliseconds(50))) {
            return;
        }
    }
    throw std::runtime_error(argv.at(0) + " did not take " + kFeedbackName + ":\n" + log());
}

FeedbackServer::~FeedbackServer() {
    if (process_->running()) {
        process_->signal(SIGTERM);
        for (int i = 0; i < 200 && process_->running(); ++i) {
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    }
}

std::vector<std::string> vibscore_feedback(const std::vector<std::string>& args) {
    std::vector<std::string> argv{required_env("VIBSCORE_FEEDBACK")};
    argv.insert(argv.end(), args.begin(), args.end());
    return argv;
}

std::vector<std::string> real_feedbackd(const std::filesystem::path& root) {
    std::vector<std::string> argv{"/usr/bin/env", "GSETTINGS_BACKEND=memory",
                                  "/usr/libexec/feedbackd"};
    if (root != "/") {
        argv.insert(argv.begin(), {"/usr/sbin/chroot", root.string()});
    }
    return argv;
}

Fbcli::Fbcli(const SessionBus& bus, const std::vector<std::string>& args) {
    std::vector<std::string> argv{"/usr/bin/fbcli"};
    argv.insert(argv.end(), args.begin(), args.end());
    started_ = std::chrono::steady_clock::now();
    process_ = std::make_unique<Process>(bus.on_this_bus(argv), dir_.path() / "fbcli.log", true);
}

std::optional<int> Fbcli::wait(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (process_->running()) {
        if (std::chrono::steady_clock::now() >= deadline) {
            return std::nullopt;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return process_->wait();
}

}  // namespace vibscore::testing
