#include "tests/support/daemon_fixture.hpp"
#include "dbus/sdbus_compat.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include "tests/support/wait_until.hpp"

extern char** environ;

namespace vibscore::testing {

Process::Process(const std::vector<std::string>& argv, const std::filesystem::path& output,
                 bool stdin_pipe) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    UniqueFd stdin_read;
    if (stdin_pipe) {
        int ends[2];
        if (::pipe2(ends, O_CLOEXEC) != 0) {
            throw std::runtime_error("cannot make a pipe for " + argv.at(0));
        }
        stdin_read = UniqueFd(ends[0]);
        stdin_ = UniqueFd(ends[1]);
        posix_spawn_file_actions_adddup2(&actions, stdin_read.get(), STDIN_FILENO);
    } else {
        posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    }
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<char*> args;
    for (const auto& arg : argv) {
        args.push_back(const_cast<char*>(arg.c_str()));
    }
    args.push_back(nullptr);
    const int result = posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (result != 0) {
        throw std::runtime_error("cannot start " + argv.at(0));
    }
}

Process::~Process() {
    if (running()) {
        ::kill(pid_, SIGKILL);
        wait();
    }
}

void Process::signal(int signo) const {
    ::kill(pid_, signo);
}

void Process::write_stdin(const std::string& text) const {
    if (::write(stdin_.get(), text.data(), text.size()) != static_cast<ssize_t>(text.size())) {
        throw std::runtime_error("cannot write to the standard input of process " +
                                 std::to_string(pid_));
    }
}

int Process::wait() {
    if (status_ < 0) {
        int status = 0;
        waitpid(pid_, &status, 0);
        status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    return status_;
}

bool Process::running() {
    if (status_ >= 0) {
        return false;
    }
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
        status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        return false;
    }
    return true;
}

sockaddr_un unix_socket_address(const std::filesystem::path& path) {
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string text = path.string();
    if (text.size() >= sizeof address.sun_path) {
        throw std::runtime_error("the socket's path is too long: " + text);
    }
    text.copy(address.sun_path, text.size());
    return address;
}

void wait_until_bus_accepts(Process& bus, const std::filesystem::path& socket,
                            const std::filesystem::path& log) {
    const sockaddr_un address = unix_socket_address(socket);
    const auto accepts = [&] {
        const UniqueFd fd(::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
        return fd.get() >= 0 && ::connect(fd.get(), reinterpret_cast<const sockaddr*>(&address),
                                          sizeof address) == 0;
    };
    bool exited = false;
    const bool ready = wait_until(
        [&] {
            exited = !bus.running();
            return exited || accepts();
        },
        std::chrono::seconds(5));
    if (!ready || exited) {
        throw std::runtime_error(std::string("the bus ") +
                                 (exited ? "exited at start" : "did not listen within 5 s") +
                                 ":\n" + read_file(log));
    }
}

HapticsClient::HapticsClient(std::unique_ptr<sdbus::IConnection> connection)
    : ProxyInterfaces(*connection, dbus::service_name("org.vibscore.Haptics1"),
                      dbus::object_path("/org/vibscore/Haptics1")),
      connection_(std::move(connection)) {
    registerProxy();
    connection_->enterEventLoopAsync();
}

HapticsClient::~HapticsClient() {
    connection_->leaveEventLoop();
    unregisterProxy();
}

void HapticsClient::record(SeenSignal signal) {
    std::lock_guard lock(mutex_);
    signals_.push_back(std::move(signal));
}

std::vector<SeenSignal> HapticsClient::signals() {
    std::lock_guard lock(mutex_);
    return signals_;
}

bool HapticsClient::wait_for(const std::function<bool(const SeenSignal&)>& match,
                             std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        for (const auto& seen : signals()) {
            if (match(seen)) {
                return true;
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
}

bool HapticsClient::wait_finished(std::uint64_t id, std::string* reason,
                                  std::chrono::milliseconds timeout) {
    return wait_for(
        [&](const SeenSignal& seen) {
            if (seen.name == "PlaybackFinished" && seen.id == id) {
                if (reason != nullptr)
                    *reason = seen.text;
                return true;
            }
            return false;
        },
        timeout);
}

void HapticsClient::onPlaybackStarted(const uint64_t& id, const std::string& score) {
    record({"PlaybackStarted", id, score});
}
void HapticsClient::onPlaybackPosition(const uint64_t& id, const uint32_t& bar,
                                       const uint32_t& symbol) {
    record({"PlaybackPosition", id, std::to_string(bar) + "." + std::to_string(symbol)});
}
void HapticsClient::onPlaybackFinished(const uint64_t& id, const std::string& reason) {
    record({"PlaybackFinished", id, reason});
}
void HapticsClient::onRegistryChanged(const std::string& kind, const std::string& name) {
    record({"RegistryChanged", 0, kind + "/" + name});
}

namespace {

constexpr const char* kPolkitBusPolicy =
    "/usr/share/dbus-1/system.d/org.freedesktop.PolicyKit1.conf";
constexpr const char* kPolkitd = "/usr/lib/polkit-1/polkitd";

// The private bus's configuration with polkit's own bus policy included as well.
std::string with_polkit_policy(const std::string& bus_config) {
    const auto end = bus_config.rfind("</busconfig>");
    if (end == std::string::npos) {
        throw std::runtime_error("the private bus configuration has no </busconfig>");
    }
    return bus_config.substr(0, end) + "  <include>" + kPolkitBusPolicy + "</include>\n" +
           bus_config.substr(end);
}

}  // namespace

DaemonFixture::DaemonFixture(const std::string& extra_config, bool with_polkit) {
    trace_ = dir_.path() / "trace.csv";
    store_ = dir_.path() / "store";
    write_config(extra_config, "trace = " + trace_.string());
    const auto socket = dir_.path() / "bus";
    bus_address_ = "unix:path=" + socket.string();
    std::string bus_config = required_env("VIBSCORE_PRIVATE_BUS_CONF");
    if (with_polkit) {
        for (const auto* needed : {kPolkitBusPolicy, kPolkitd}) {
            if (!std::filesystem::exists(needed)) {
                throw std::runtime_error(std::string(needed) +
                                         " is missing: install polkitd (./dev test does)");
            }
        }
        bus_config =
            dir_.write("polkit-bus.conf", with_polkit_policy(read_file(bus_config))).string();
    }
    bus_ = std::make_unique<Process>(
        std::vector<std::string>{"/usr/bin/dbus-daemon", "--config-file=" + bus_config,
                                 "--address=" + bus_address_, "--nofork", "--nopidfile"},
        dir_.path() / "bus.log");
    wait_until_bus_accepts(*bus_, socket, dir_.path() / "bus.log");
    // Other users (the permission tests, polkitd) must reach the socket and the trace.
    std::filesystem::permissions(dir_.path(), std::filesystem::perms::all);
    setenv("DBUS_SYSTEM_BUS_ADDRESS", bus_address_.c_str(), 1);
    if (with_polkit) {
        // polkitd starts as root and becomes user polkitd itself.
        polkit_ = std::make_unique<Process>(
            std::vector<std::string>{"/usr/bin/env", "DBUS_SYSTEM_BUS_ADDRESS=" + bus_address_,
                                     kPolkitd, "--no-debug"},
            dir_.path() / "polkitd.log");
        wait_for_name("org.freedesktop.PolicyKit1", *polkit_, "polkitd.log");
    }
    start_daemon();
}

DaemonFixture::~DaemonFixture() {
    daemon_.reset();
    if (polkit_) {
        polkit_->signal(SIGCONT);  // a test may have stopped it
    }
    polkit_.reset();
    bus_.reset();
}

void DaemonFixture::wait_for_name(const std::string& name, Process& owner, const std::string& log) {
    for (int i = 0; i < 1000; ++i) {
        const auto names = busctl({"list", "--no-pager", "--no-legend"});
        if (names.out.find(name) != std::string::npos) {
            return;
        }
        if (!owner.running()) {
            throw std::runtime_error(name + "'s owner exited at start:\n" +
                                     read_file(dir_.path() / log));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    throw std::runtime_error(name + " was not taken:\n" + read_file(dir_.path() / log));
}

void DaemonFixture::start_daemon() {
    daemon_ =
        std::make_unique<Process>(std::vector<std::string>{required_env("VIBSCORED"), "--config",
                                                           config_.string(), "--verbose"},
                                  dir_.path() / "daemon.log");
    wait_for_name("org.vibscore.Haptics1", *daemon_, "daemon.log");
}

int DaemonFixture::stop_daemon() {
    daemon_->signal(SIGTERM);
    return daemon_->wait();
}

void DaemonFixture::write_config(const std::string& daemon_lines, const std::string& sim_lines) {
    // The fixture's driver and the checkout's shipped documents, unless the lines set their own
    // (a key set twice is an error).
    const auto sets = [&](const std::string& key) {
        return daemon_lines.starts_with(key + " =") ||
               daemon_lines.find("\n" + key + " =") != std::string::npos;
    };
    const std::string driver = sets("driver") ? "" : "driver = sim\n";
    const std::string shipped =
        sets("shipped") ? "" : "shipped = " + required_env("VIBSCORE_CLEFS") + "\n";
    config_ = dir_.write("vibscored.conf", "[daemon]\n" + driver + shipped +
                                               "store = " + store_.string() + "\n" + daemon_lines +
                                               "\n[sim]\n" + sim_lines + "\n");
}

void DaemonFixture::signal_daemon(int signo) const {
    daemon_->signal(signo);
}

void DaemonFixture::kill_daemon() {
    daemon_->signal(SIGKILL);
    daemon_->wait();
}

int DaemonFixture::wait_daemon() {
    return daemon_->wait();
}

std::string DaemonFixture::daemon_log() const {
    std::ifstream in(dir_.path() / "daemon.log");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::unique_ptr<HapticsClient> DaemonFixture::client() const {
    return std::make_unique<HapticsClient>(sdbus::createSystemBusConnection());
}

CommandResult DaemonFixture::busctl(const std::vector<std::string>& args, uid_t uid) const {
    std::vector<std::string> argv;
    if (uid != 0) {
        argv = {"/usr/bin/setpriv", "--reuid=" + std::to_string(uid),
                "--regid=" + std::to_string(uid), "--clear-groups", "--"};
    }
    argv.insert(argv.end(), {"/usr/bin/env", "DBUS_SYSTEM_BUS_ADDRESS=" + bus_address_,
                             "/usr/bin/busctl", "--system"});
    argv.insert(argv.end(), args.begin(), args.end());
    return run_command(argv);
}

CommandResult DaemonFixture::call(const std::vector<std::string>& args, uid_t uid) const {
    std::vector<std::string> full{"call", "org.vibscore.Haptics1", "/org/vibscore/Haptics1",
                                  "org.vibscore.Haptics1"};
    full.insert(full.end(), args.begin(), args.end());
    return busctl(full, uid);
}

std::vector<DaemonFixture::TraceRow> DaemonFixture::trace_rows() const {
    std::ifstream in(trace_);
    std::string line;
    std::getline(in, line);
    std::vector<TraceRow> rows;
    while (std::getline(in, line)) {
        TraceRow row{};
        if (std::sscanf(line.c_str(), "%ld,%lf,%lf,%lf", &row.time_ns, &row.amplitude,
                        &row.frequency_hz, &row.response) == 4) {
            rows.push_back(row);
        }
    }
    return rows;
}

}  // namespace vibscore::testing
