#pragma once

#include <sdbus-c++/sdbus-c++.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

// sdbus-c++ 1.x (Debian 12) and 2.x (Debian 13, Yocto, postmarketOS) in one tree. The two
// generations differ in a few spellings, not in what they do; every difference the code meets
// is answered here and nowhere else, so the rest of the tree reads the same on both. meson
// defines VIBSCORE_SDBUS_CPP_MAJOR from the library's pkg-config version.
//
// What 2.x changed, and how this header answers it:
// - Names are typed (ServiceName, ObjectPath, InterfaceName, MemberName, Error::Name) with
//   explicit constructors: service_name(), object_path(), bus_error(), create_proxy().
// - The poll data's absolute timeout is a std::chrono::microseconds (max() = none) instead of
//   `timeout_usec` (UINT64_MAX = none), and 2.x adds an event fd: poll_data().
// - processPendingRequest() became processPendingEvent(): process_pending().
// - Match callbacks and the currently processed message pass Message by value (1.x: by
//   reference; its Message cannot be copied): add_match() and with_current_message() hand a
//   reference to the callback in both.
// - Variant::peekValueType() returns a const char* (1.x: std::string), so `== "s"` would
//   compare pointers: variant_signature() always gives a std::string.
// - onPropertiesChanged() takes typed names: ChangedProperties, PropertyName.
// - An asynchronous call's reply handler gets std::optional<Error> (1.x: const Error*):
//   AsyncCallError and failure_of().
#ifndef VIBSCORE_SDBUS_CPP_MAJOR
#error "VIBSCORE_SDBUS_CPP_MAJOR must be defined by the build (dbus/meson.build)"
#endif

namespace vibscore::dbus {

#if VIBSCORE_SDBUS_CPP_MAJOR >= 2
using ServiceName = sdbus::ServiceName;
using InterfaceName = sdbus::InterfaceName;
using PropertyName = sdbus::PropertyName;
#else
using ServiceName = std::string;
using InterfaceName = std::string;
using PropertyName = std::string;
#endif
// What Properties_proxy::onPropertiesChanged() is given.
using ChangedProperties = std::map<PropertyName, sdbus::Variant>;

inline ServiceName service_name(std::string_view name) {
    return ServiceName(std::string(name));
}

inline sdbus::ObjectPath object_path(std::string_view path) {
    return sdbus::ObjectPath(std::string(path));
}

inline InterfaceName interface_name(std::string_view name) {
    return InterfaceName(std::string(name));
}

// The error a method throws to send the named D-Bus error `name` with `message`.
inline sdbus::Error bus_error(std::string_view name, std::string message) {
#if VIBSCORE_SDBUS_CPP_MAJOR >= 2
    return sdbus::Error(sdbus::Error::Name(std::string(name)), std::move(message));
#else
    return sdbus::Error(std::string(name), std::move(message));
#endif
}

// A proxy for calling `destination`'s object at `path` over `connection`, without a thread of
// its own: replies and signals are read by whoever serves the connection.
inline std::unique_ptr<sdbus::IProxy> create_proxy(sdbus::IConnection& connection,
                                                   std::string_view destination,
                                                   std::string_view path) {
    return sdbus::createProxy(connection, service_name(destination), object_path(path));
}

inline void request_name(sdbus::IConnection& connection, std::string_view name) {
    connection.requestName(service_name(name));
}

inline void release_name(sdbus::IConnection& connection, std::string_view name) {
    connection.releaseName(service_name(name));
}

// What an outside event loop must wait for on behalf of a connection, in one shape for both
// generations.
struct PollData {
    int fd = -1;
    short events = 0;
    // The absolute CLOCK_MONOTONIC time (µs) by which the connection must be processed, if any.
    std::optional<std::uint64_t> deadline_us;
    // The same deadline relative to now, for poll(2).
    std::optional<std::chrono::microseconds> relative_timeout;
    // 2.x only: an eventfd the library signals when another thread queued work; -1 in 1.x.
    int event_fd = -1;
};

inline PollData poll_data(sdbus::IConnection& connection) {
    const auto raw = connection.getEventLoopPollData();
    PollData data;
    data.fd = raw.fd;
    data.events = raw.events;
#if VIBSCORE_SDBUS_CPP_MAJOR >= 2
    if (raw.timeout != std::chrono::microseconds::max()) {
        data.deadline_us = static_cast<std::uint64_t>(raw.timeout.count());
        data.relative_timeout = raw.getRelativeTimeout();
    }
    data.event_fd = raw.eventFd;
#else
    if (raw.timeout_usec != UINT64_MAX) {
        data.deadline_us = raw.timeout_usec;
        data.relative_timeout = raw.getRelativeTimeout();
    }
#endif
    return data;
}

// Processes one pending incoming or outgoing event; false when there was none.
inline bool process_pending(sdbus::IConnection& connection) {
#if VIBSCORE_SDBUS_CPP_MAJOR >= 2
    return connection.processPendingEvent();
#else
    return connection.processPendingRequest();
#endif
}

// Calls `handler` with each message matching `rule` until the returned slot is destroyed.
[[nodiscard]] inline sdbus::Slot add_match(sdbus::IConnection& connection, const std::string& rule,
                                           std::function<void(sdbus::Message&)> handler) {
#if VIBSCORE_SDBUS_CPP_MAJOR >= 2
    return connection.addMatch(
        rule, [handler = std::move(handler)](sdbus::Message message) { handler(message); },
        sdbus::return_slot);
#else
    return connection.addMatch(rule, std::move(handler));
#endif
}

// Calls `use` with the message the object is handling now (only inside a method handler) and
// returns what it returns.
template <typename Use>
decltype(auto) with_current_message(const sdbus::IObject& object, Use&& use) {
#if VIBSCORE_SDBUS_CPP_MAJOR >= 2
    const sdbus::Message message = object.getCurrentlyProcessedMessage();
    return use(message);
#else
    return use(*object.getCurrentlyProcessedMessage());
#endif
}

// Announces that the properties `names` of `interface` on `object` changed (PropertiesChanged).
inline void emit_properties_changed(sdbus::IObject& object, std::string_view interface,
                                    std::initializer_list<std::string_view> names) {
    std::vector<PropertyName> typed;
    for (const auto name : names) {
        typed.emplace_back(std::string(name));
    }
    object.emitPropertiesChangedSignal(interface_name(interface), typed);
}

// The D-Bus signature of the value a variant holds ("s", "a{ss}", ...).
inline std::string variant_signature(const sdbus::Variant& value) {
    return std::string(value.peekValueType());
}

// The sender of `message`, as a string in both generations.
inline std::string sender_of(const sdbus::Message& message) {
#if VIBSCORE_SDBUS_CPP_MAJOR >= 2
    const char* sender = message.getSender();
    return sender != nullptr ? std::string(sender) : std::string();
#else
    return message.getSender();
#endif
}

// What an asynchronous call's reply handler is given as its first argument: the error, if the
// call failed (1.x: a pointer, null on success; 2.x: an optional).
#if VIBSCORE_SDBUS_CPP_MAJOR >= 2
using AsyncCallError = std::optional<sdbus::Error>;
inline const sdbus::Error* failure_of(const AsyncCallError& error) {
    return error ? &*error : nullptr;
}
#else
using AsyncCallError = const sdbus::Error*;
inline const sdbus::Error* failure_of(AsyncCallError error) {
    return error;
}
#endif

// The error's name as a string in both generations.
inline std::string error_name(const sdbus::Error& error) {
    return std::string(error.getName());
}

}  // namespace vibscore::dbus
