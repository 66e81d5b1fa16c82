#pragma once

#include <sys/types.h>
#include <sys/un.h>

#include <sdbus-c++/sdbus-c++.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/unique_fd.hpp"
#include "haptics1-proxy.h"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::testing {

// A child process, killed and reaped when this goes out of scope.
class Process {
  public:
    // stdout and stderr go to `output`. stdin is /dev/null, or with `stdin_pipe` a pipe that
    // stays open until close_stdin() (some programs act on end of input, fbcli for one).
    Process(const std::vector<std::string>& argv, const std::filesystem::path& output,
            bool stdin_pipe = false);
    ~Process();
    Process(const Process&) = delete;
    Process& operator=(const Process&) = delete;

    pid_t pid() const { return pid_; }
    void signal(int signo) const;
    // Waits for the exit; returns the exit code, or 128 + signal.
    int wait();
    bool running();
    void write_stdin(const std::string& text) const;
    void close_stdin() { stdin_.close(); }

  private:
    pid_t pid_ = -1;
    int status_ = -1;
    UniqueFd stdin_;
};

// The address of the Unix socket at `path`; throws std::runtime_error when the path is too long
// for one.
sockaddr_un unix_socket_address(const std::filesystem::path& path);

// Waits until the dbus-daemon `bus`, logging to `log`, accepts connections on its Unix socket
// `socket`; throws with the log if it exits or has not within 5 s. Its socket file appears at
// bind(), before it listens: a client that connects in between is refused ("Connection
// refused"), as a test that waited only for the file once was.
void wait_until_bus_accepts(Process& bus, const std::filesystem::path& socket,
                            const std::filesystem::path& log);

// A signal seen by the test client, in arrival order.
struct SeenSignal {
    std::string name;  // PlaybackStarted, PlaybackPosition, PlaybackFinished, RegistryChanged
    std::uint64_t id = 0;
    std::string text;  // score, reason, kind/name, or "bar.symbol"
};

// A typed client of org.vibscore.Haptics1 on the private bus, recording every signal.
class HapticsClient : public sdbus::ProxyInterfaces<org::vibscore::Haptics1_proxy> {
  public:
    explicit HapticsClient(std::unique_ptr<sdbus::IConnection> connection);
    ~HapticsClient();

    std::vector<SeenSignal> signals();
    // Waits until a signal satisfying `match` arrives; false after `timeout`.
    bool wait_for(const std::function<bool(const SeenSignal&)>& match,
                  std::chrono::milliseconds timeout = std::chrono::seconds(10));
    bool wait_finished(std::uint64_t id, std::string* reason = nullptr,
                       std::chrono::milliseconds timeout = std::chrono::seconds(10));

  private:
    void onPlaybackStarted(const uint64_t& id, const std::string& score) override;
    void onPlaybackPosition(const uint64_t& id, const uint32_t& bar,
                            const uint32_t& symbol) override;
    void onPlaybackFinished(const uint64_t& id, const std::string& reason) override;
    void onRegistryChanged(const std::string& kind, const std::string& name) override;
    void record(SeenSignal signal);

    std::unique_ptr<sdbus::IConnection> connection_;
    std::mutex mutex_;
    std::vector<SeenSignal> signals_;
};

// A private bus with the real policy, and the real vibscored on it with the sim driver. With
// `with_polkit`, Debian's polkitd serves the bus too (it becomes user polkitd; its own bus
// policy is included), started before vibscored; polkit() is its process.
class DaemonFixture {
  public:
    explicit DaemonFixture(const std::string& extra_config = "", bool with_polkit = false);
    ~DaemonFixture();

    Process& polkit() { return *polkit_; }

    void start_daemon();
    // SIGTERM, then the exit code.
    int stop_daemon();
    void kill_daemon();
    // Waits for the daemon to end by itself (a crash): its exit code, or 128 + the signal.
    int wait_daemon();
    void signal_daemon(int signo) const;
    // Rewrites the configuration: extra [daemon] lines (a "driver =" or "shipped =" among them
    // replaces the fixture's sim or the checkout's clefs/), and the [sim] section's lines.
    void write_config(const std::string& daemon_lines, const std::string& sim_lines);

    const std::string& bus_address() const { return bus_address_; }
    const std::filesystem::path& trace() const { return trace_; }
    const std::filesystem::path& store() const { return store_; }
    const std::filesystem::path& config() const { return config_; }
    std::string daemon_log() const;

    std::unique_ptr<HapticsClient> client() const;
    // busctl --system against the private bus; as another user when uid is set.
    CommandResult busctl(const std::vector<std::string>& args, uid_t uid = 0) const;
    // busctl call on the vibscore object: busctl_call({"Play", "sa{sv}", "touch-tick", "0"}).
    CommandResult call(const std::vector<std::string>& args, uid_t uid = 0) const;

    // The trace file's rows after the header: time_ns, amplitude, frequency_hz, response.
    struct TraceRow {
        std::int64_t time_ns;
        double amplitude, frequency_hz, response;
    };
    std::vector<TraceRow> trace_rows() const;

  private:
    // Waits until `name` is on the bus; throws with the owner's log when it exits first.
    void wait_for_name(const std::string& name, Process& owner, const std::string& log);

    TempDir dir_;
    std::filesystem::path trace_, store_, config_;
    std::string bus_address_;
    std::unique_ptr<Process> bus_;
    std::unique_ptr<Process> polkit_;
    std::unique_ptr<Process> daemon_;
};

}  // namespace vibscore::testing
