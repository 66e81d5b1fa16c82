#include "client/editor/daemon_watch.hpp"

#include "dbus/haptics1_names.hpp"
#include "dbus/name_owner_watch.hpp"
#include "dbus/sdbus_compat.hpp"

namespace vibscore::client {

DaemonWatch::DaemonWatch(sdbus::IConnection& connection) : connection_(connection) {
    match_ = dbus::watch_name_owner(connection_, haptics1::kBusName,
                                    [this](const dbus::NameOwnerChange& change) {
                                        const std::lock_guard lock(mutex_);
                                        if (!change.old_owner.empty()) {
                                            left_.insert(change.old_owner);
                                        }
                                        if (!change.new_owner.empty() && left_.count(owner_) != 0) {
                                            restarted_ = true;
                                        }
                                    });
}

void DaemonWatch::follow() {
    std::string owner;
    try {
        const auto bus =
            dbus::create_proxy(connection_, "org.freedesktop.DBus", "/org/freedesktop/DBus");
        bus->callMethod("GetNameOwner")
            .onInterface("org.freedesktop.DBus")
            .withArguments(std::string(haptics1::kBusName))
            .storeResultsTo(owner);
    } catch (const sdbus::Error&) {
        // Nobody owns the name any more: the daemon that answered has already left.
    }
    const std::lock_guard lock(mutex_);
    owner_ = owner;
    restarted_ = false;
}

std::optional<std::string> DaemonWatch::gone() {
    const std::lock_guard lock(mutex_);
    if (!owner_.empty() && left_.count(owner_) == 0) {
        return std::nullopt;
    }
    return restarted_ ? "vibscored was restarted" : "vibscored left the bus";
}

}  // namespace vibscore::client
