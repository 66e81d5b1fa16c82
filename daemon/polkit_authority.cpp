#include "daemon/polkit_authority.hpp"

#include <sdbus-c++/Error.h>
#include <sdbus-c++/Types.h>

#include <chrono>
#include <map>
#include <stdexcept>
#include <string>

#include "dbus/sdbus_compat.hpp"

namespace vibscore::daemon {

namespace {

constexpr const char* kPolkitName = "org.freedesktop.PolicyKit1";
constexpr const char* kAuthorityPath = "/org/freedesktop/PolicyKit1/Authority";
constexpr const char* kAuthorityInterface = "org.freedesktop.PolicyKit1.Authority";
// Bounds how long a hung polkit can hold a call (the daemon waits for its reply).
constexpr auto kReplyTimeout = std::chrono::seconds(5);

bool means_not_on_the_bus(const std::string& error_name) {
    return error_name == "org.freedesktop.DBus.Error.ServiceUnknown" ||
           error_name == "org.freedesktop.DBus.Error.NameHasNoOwner";
}

}  // namespace

BusPolkitAuthority::BusPolkitAuthority(sdbus::IConnection& connection)
    : proxy_(dbus::create_proxy(connection, kPolkitName, kAuthorityPath)) {}

PolkitAnswer BusPolkitAuthority::check(const std::string& sender, std::string_view action_id) {
    using Subject = sdbus::Struct<std::string, std::map<std::string, sdbus::Variant>>;
    using Result = sdbus::Struct<bool, bool, std::map<std::string, std::string>>;
    const Subject subject{std::string("system-bus-name"),
                          std::map<std::string, sdbus::Variant>{{"name", sdbus::Variant(sender)}}};
    const std::map<std::string, std::string> details;
    const std::uint32_t flags = 0;  // no AllowUserInteraction: a daemon call cannot wait for it
    Result result;
    try {
        proxy_->callMethod("CheckAuthorization")
            .onInterface(kAuthorityInterface)
            .withTimeout(kReplyTimeout)
            .withArguments(subject, std::string(action_id), details, flags, std::string())
            .storeResultsTo(result);
    } catch (const sdbus::Error& error) {
        if (means_not_on_the_bus(dbus::error_name(error))) {
            return PolkitAnswer::unavailable;
        }
        throw std::runtime_error(dbus::error_name(error) + ": " + error.getMessage());
    }
    return result.get<0>() ? PolkitAnswer::authorized : PolkitAnswer::not_authorized;
}

}  // namespace vibscore::daemon
