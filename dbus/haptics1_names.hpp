#pragma once

#include <string_view>

// The names of org.vibscore.Haptics1 on the bus, as org.vibscore.Haptics1.xml documents them:
// the one spelling of each, for the daemon that owns them and the clients that call it.
namespace vibscore::haptics1 {

inline constexpr const char* kBusName = "org.vibscore.Haptics1";
inline constexpr const char* kObjectPath = "/org/vibscore/Haptics1";
inline constexpr const char* kInterface = "org.vibscore.Haptics1";

// The named errors the daemon sends; every one begins with kErrorPrefix.
namespace errors {
inline constexpr std::string_view kErrorPrefix = "org.vibscore.Haptics1.Error.";
inline constexpr const char* kInvalidDocument = "org.vibscore.Haptics1.Error.InvalidDocument";
// A number outside the range its argument or option allows (the message names both).
inline constexpr const char* kOutOfRange = "org.vibscore.Haptics1.Error.OutOfRange";
inline constexpr const char* kNotFound = "org.vibscore.Haptics1.Error.NotFound";
inline constexpr const char* kPermissionDenied = "org.vibscore.Haptics1.Error.PermissionDenied";
inline constexpr const char* kLimitExceeded = "org.vibscore.Haptics1.Error.LimitExceeded";
inline constexpr const char* kBusy = "org.vibscore.Haptics1.Error.Busy";
inline constexpr const char* kCoolingDown = "org.vibscore.Haptics1.Error.CoolingDown";
inline constexpr const char* kDevice = "org.vibscore.Haptics1.Error.Device";
inline constexpr const char* kNoAccelerometer = "org.vibscore.Haptics1.Error.NoAccelerometer";
inline constexpr const char* kUntrusted = "org.vibscore.Haptics1.Error.Untrusted";

// Not ours: what the bus says when vibscored is not there, and the generic failure a method
// sends when none of the names above fits.
inline constexpr const char* kServiceUnknown = "org.freedesktop.DBus.Error.ServiceUnknown";
inline constexpr const char* kNameHasNoOwner = "org.freedesktop.DBus.Error.NameHasNoOwner";
inline constexpr const char* kFailed = "org.freedesktop.DBus.Error.Failed";
}  // namespace errors

}  // namespace vibscore::haptics1
