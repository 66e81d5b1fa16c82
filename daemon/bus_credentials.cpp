#include "daemon/bus_credentials.hpp"

#include <cstdint>

#include "dbus/sdbus_compat.hpp"

namespace vibscore::daemon {

BusCredentials::BusCredentials(sdbus::IConnection& connection)
    : proxy_(dbus::create_proxy(connection, "org.freedesktop.DBus", "/org/freedesktop/DBus")) {}

uid_t BusCredentials::uid_of(const std::string& sender) {
    std::uint32_t uid = 0;
    proxy_->callMethod("GetConnectionUnixUser")
        .onInterface("org.freedesktop.DBus")
        .withArguments(sender)
        .storeResultsTo(uid);
    return static_cast<uid_t>(uid);
}

}  // namespace vibscore::daemon
