#pragma once

#include <sdbus-c++/Error.h>

#include <exception>

// The bus boundary: what the daemon's parts throw becomes a named D-Bus error
// (dbus/haptics1_names.hpp), in one place, so that nothing a caller sends can stop the daemon
// and every refusal has a name a client can act on.
namespace vibscore::daemon {

// The named error for `error`, thrown while handling `method`: RequestError, RegistryError and
// DocumentError by their codes, PlayerBusy as Busy, CoolingDown as CoolingDown, DeviceError and
// PlaybackStuck as Device; anything else is logged and becomes org.freedesktop.DBus.Error.Failed
// naming the method.
sdbus::Error to_bus_error(const char* method, const std::exception_ptr& error);

// Runs a method body; whatever it throws leaves as a named D-Bus error.
template <typename Body>
auto guarded(const char* method, Body&& body) -> decltype(body()) {
    try {
        return body();
    } catch (const sdbus::Error&) {
        throw;
    } catch (...) {
        throw to_bus_error(method, std::current_exception());
    }
}

}  // namespace vibscore::daemon
