#include "daemon/polkit_authority.hpp"

#include <chrono>
#include <map>
#include <string>

#include "dbus/sdbus_compat.hpp"

namespace vibscore::daemon {

namespace {

constexpr const char* kPolkitName = "org.freedesktop.PolicyKit1";
constexpr const char* kAuthorityPath = "/org/freedesktop/PolicyKit1/Authority";
constexpr const char* kAuthorityInterface = "org.freedesktop.PolicyKit1.Authority";
// How long polkit may take before its answer counts as a failure. Nobody else waits meanwhile:
// only the call that asked is held.
constexpr auto kReplyTimeout = std::chrono::seconds(5);

bool means_not_on_the_bus(const std::string& error_name) {
    return error_name == "org.freedesktop.DBus.Error.ServiceUnknown" ||
           error_name == "org.freedesktop.DBus.Error.NameHasNoOwner";
}

}  // namespace

BusPolkitAuthority::BusPolkitAuthority(sdbus::IConnection& connection)
    : proxy_(dbus::create_proxy(connection, kPolkitName, kAuthorityPath)) {}

void BusPolkitAuthority::check(const std::string& sender, std::string_view action_id,
                               Answered answered) {
    using Subject = sdbus::Struct<std::string, std::map<std::string, sdbus::Variant>>;
    using Result = sdbus::Struct<bool, bool, std::map<std::string, std::string>>;
    const Subject subject{std::string("system-bus-name"),
                          std::map<std::string, sdbus::Variant>{{"name", sdbus::Variant(sender)}}};
    const std::map<std::string, std::string> details;
    const std::uint32_t flags = 0;  // no AllowUserInteraction: a daemon call cannot wait for it
    try {
        proxy_->callMethodAsync("CheckAuthorization")
            .onInterface(kAuthorityInterface)
            .withTimeout(kReplyTimeout)
            .withArguments(subject, std::string(action_id), details, flags, std::string())
            .uponReplyInvoke([answered](dbus::AsyncCallError error, Result result) {
                if (const sdbus::Error* failure = dbus::failure_of(error)) {
                    const std::string name = dbus::error_name(*failure);
                    if (means_not_on_the_bus(name)) {
                        answered(PolkitAnswer::unavailable, {});
                    } else {
                        answered(PolkitAnswer::failed, name + ": " + failure->getMessage());
                    }
                    return;
                }
                answered(result.get<0>() ? PolkitAnswer::authorized : PolkitAnswer::not_authorized,
                         {});
            });
    } catch (const sdbus::Error& error) {
        // The call could not even be sent (the connection is closing).
        answered(PolkitAnswer::failed, dbus::error_name(error) + ": " + error.getMessage());
    }
}

}  // namespace vibscore::daemon
