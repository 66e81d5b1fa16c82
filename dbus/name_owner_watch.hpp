#pragma once

#include "dbus/sdbus_compat.hpp"

#include <functional>
#include <string>
#include <utility>

// The bus driver's NameOwnerChanged, the one way the daemon, the client and vibscore-feedback
// learn that a name changed hands or a connection left the bus.
namespace vibscore::dbus {

struct NameOwnerChange {
    std::string name;       // a well-known name, or a connection's unique name (":1.42")
    std::string old_owner;  // empty: the name was just taken
    std::string new_owner;  // empty: the name was released (for a unique name: it left the bus)
};

// Calls `changed` for each NameOwnerChanged of `name` (every name when it is empty) until the
// returned slot is destroyed.
[[nodiscard]] inline sdbus::Slot watch_name_owner(
    sdbus::IConnection& connection, const std::string& name,
    std::function<void(const NameOwnerChange&)> changed) {
    std::string rule =
        "type='signal',sender='org.freedesktop.DBus',interface='org.freedesktop.DBus',"
        "member='NameOwnerChanged'";
    if (!name.empty()) {
        rule += ",arg0='" + name + "'";
    }
    return add_match(connection, rule, [changed = std::move(changed)](sdbus::Message& message) {
        NameOwnerChange change;
        message >> change.name >> change.old_owner >> change.new_owner;
        changed(change);
    });
}

// Calls `left` with the unique name of each connection that leaves the bus, until the returned
// slot is destroyed.
[[nodiscard]] inline sdbus::Slot watch_connections_leaving(
    sdbus::IConnection& connection, std::function<void(const std::string& unique_name)> left) {
    return watch_name_owner(
        connection, "", [left = std::move(left)](const NameOwnerChange& change) {
            if (change.new_owner.empty() && !change.name.empty() && change.name.front() == ':') {
                left(change.name);
            }
        });
}

}  // namespace vibscore::dbus
