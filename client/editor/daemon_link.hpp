#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace vibscore::editor {

// A playback signal from the daemon.
struct PlaybackEvent {
    enum class Kind { position, finished };
    Kind kind = Kind::position;
    std::uint64_t id = 0;
    std::uint32_t bar = 0, symbol = 0;  // position: counted from 0 as in the document
    std::string reason;                 // finished: "completed", "stopped", ...
};

// vibscored refused or could not be reached; the message says which and why, in words.
class DaemonError : public std::runtime_error {
  public:
    DaemonError(std::string name, const std::string& message)
        : std::runtime_error(message), name_(std::move(name)) {}
    // The D-Bus error name, e.g. org.vibscore.Haptics1.Error.NotFound.
    const std::string& name() const { return name_; }
    bool not_found() const;

  private:
    std::string name_;
};

// The editor's connection to vibscored on the system bus (or DBUS_SYSTEM_BUS_ADDRESS). The bus
// is served from the editor's own poll loop: no threads. Calls throw DaemonError.
class DaemonLink {
  public:
    DaemonLink();
    ~DaemonLink();
    DaemonLink(const DaemonLink&) = delete;
    DaemonLink& operator=(const DaemonLink&) = delete;

    std::uint64_t play(const std::string& document, std::size_t start_bar);
    // Plays an inline score with clefs sent along (by the href the score declares them by),
    // not followed: a clef heard while it is edited. A newer one takes over.
    std::uint64_t audition(const std::string& document,
                           const std::map<std::string, std::string>& clefs);
    void stop(std::uint64_t id);
    void compose(const std::string& name, const std::string& document);
    std::string get(const std::string& kind, const std::string& name);
    std::vector<std::string> list(const std::string& kind);
    // "shipped", "stored" or "stored-over-shipped" (Origin).
    std::string origin(const std::string& kind, const std::string& name);
    // The actuator the daemon declares (Haptics1.Actuator), empty when none is.
    std::map<std::string, std::string> actuator();

    // For poll(): the bus descriptor, the events to wait for, and how long at most (ms, -1
    // for no limit).
    int fd() const;
    short events() const;
    int timeout_ms() const;
    // Serves whatever the bus has; returns the playback signals that came in.
    std::vector<PlaybackEvent> process();

  private:
    class Proxy;
    std::unique_ptr<Proxy> proxy_;
};

}  // namespace vibscore::editor
