#include "client/editor/daemon_link.hpp"

#include <sdbus-c++/sdbus-c++.h>

#include <algorithm>
#include <map>
#include <set>

#include "client/editor/daemon_errors.hpp"
#include "client/editor/daemon_watch.hpp"
#include "dbus/haptics1_names.hpp"
#include "dbus/sdbus_compat.hpp"
#include "haptics1-proxy.h"

namespace vibscore::editor {

namespace {

DaemonError explain(const sdbus::Error& error) {
    return {error.getName(), client::describe_daemon_error(error.getName(), error.getMessage())};
}

template <typename Call>
auto guarded(Call&& call) {
    try {
        return call();
    } catch (const sdbus::Error& error) {
        throw explain(error);
    }
}

}  // namespace

bool DaemonError::not_found() const {
    return name_ == haptics1::errors::kNotFound;
}

class DaemonLink::Proxy : public sdbus::ProxyInterfaces<org::vibscore::Haptics1_proxy> {
  public:
    explicit Proxy(std::unique_ptr<sdbus::IConnection> connection)
        : ProxyInterfaces(*connection, dbus::service_name(haptics1::kBusName),
                          dbus::object_path(haptics1::kObjectPath)),
          connection_(std::move(connection)),
          watch_(*connection_) {
        registerProxy();
    }
    ~Proxy() { unregisterProxy(); }

    sdbus::IConnection& connection() { return *connection_; }

    // A playback this link started; the daemon that plays it is followed until it finishes.
    void started(std::uint64_t id) {
        watch_.follow();
        playing_.insert(id);
    }

    // What came in, with a finish for each playback whose daemon has gone (it sends nothing).
    std::vector<PlaybackEvent> take() {
        auto events = std::exchange(events_, {});
        for (const auto& event : events) {
            if (event.kind == PlaybackEvent::Kind::finished) {
                playing_.erase(event.id);
            }
        }
        if (!playing_.empty()) {
            if (const auto gone = watch_.gone()) {
                for (const auto id : playing_) {
                    events.push_back({PlaybackEvent::Kind::finished, id, 0, 0, *gone});
                }
                playing_.clear();
            }
        }
        return events;
    }

  private:
    void onPlaybackStarted(const uint64_t&, const std::string&) override {}
    void onPlaybackPosition(const uint64_t& id, const uint32_t& bar,
                            const uint32_t& symbol) override {
        events_.push_back({PlaybackEvent::Kind::position, id, bar, symbol, {}});
    }
    void onPlaybackFinished(const uint64_t& id, const std::string& reason) override {
        events_.push_back({PlaybackEvent::Kind::finished, id, 0, 0, reason});
    }
    void onRegistryChanged(const std::string&, const std::string&) override {}

    std::unique_ptr<sdbus::IConnection> connection_;
    client::DaemonWatch watch_;
    std::vector<PlaybackEvent> events_;
    std::set<std::uint64_t> playing_;
};

DaemonLink::DaemonLink() {
    try {
        proxy_ = std::make_unique<Proxy>(sdbus::createSystemBusConnection());
    } catch (const sdbus::Error& error) {
        throw DaemonError(error.getName(), "cannot reach the system bus: " + error.getMessage());
    }
}

DaemonLink::~DaemonLink() = default;

std::uint64_t DaemonLink::play(const std::string& document, std::size_t start_bar) {
    return guarded([&] {
        std::map<std::string, sdbus::Variant> options;
        options["start-bar"] = sdbus::Variant(static_cast<std::uint32_t>(start_bar));
        const auto id = proxy_->Play(document, options);
        proxy_->started(id);
        return id;
    });
}

std::uint64_t DaemonLink::audition(const std::string& document,
                                   const std::map<std::string, std::string>& clefs) {
    return guarded([&] {
        std::map<std::string, sdbus::Variant> options;
        options["clefs"] = sdbus::Variant(clefs);
        options["usage"] = sdbus::Variant(std::string("touch"));
        return proxy_->Play(document, options);
    });
}

void DaemonLink::stop(std::uint64_t id) {
    guarded([&] {
        proxy_->Stop(id);
        return 0;
    });
}

void DaemonLink::compose(const std::string& name, const std::string& document) {
    guarded([&] {
        proxy_->Compose(name, document);
        return 0;
    });
}

std::string DaemonLink::get(const std::string& kind, const std::string& name) {
    return guarded([&] { return proxy_->Get(kind, name); });
}

std::string DaemonLink::origin(const std::string& kind, const std::string& name) {
    return guarded([&] { return proxy_->Origin(kind, name); });
}

std::map<std::string, std::string> DaemonLink::actuator() {
    return guarded([&] { return proxy_->Actuator(); });
}

std::vector<std::string> DaemonLink::list(const std::string& kind) {
    return guarded([&] {
        std::vector<std::string> names;
        for (const auto& entry : proxy_->List(kind)) {
            names.push_back(entry.get<0>());
        }
        return names;
    });
}

int DaemonLink::fd() const {
    return dbus::poll_data(proxy_->connection()).fd;
}

short DaemonLink::events() const {
    return dbus::poll_data(proxy_->connection()).events;
}

int DaemonLink::timeout_ms() const {
    const auto relative = dbus::poll_data(proxy_->connection()).relative_timeout;
    if (!relative) {
        return -1;
    }
    // Rounded up, so poll does not wake just before the bus wants serving.
    const auto ms = (relative->count() + 999) / 1000;
    return static_cast<int>(std::min<long long>(ms, 60'000));
}

std::vector<PlaybackEvent> DaemonLink::process() {
    try {
        while (dbus::process_pending(proxy_->connection())) {
        }
    } catch (const sdbus::Error& error) {
        throw explain(error);
    }
    return proxy_->take();
}

}  // namespace vibscore::editor
