#pragma once

#include <map>
#include <string>

#include "dbus/haptics1_names.hpp"

namespace vibscore::client {

// A D-Bus error from vibscored in plain words, for people: its named errors become
// "not found: <message>", "not permitted: <message>" and so on; a daemon that is not there
// says so. Shared by the command-line verbs and the editor's status line.
inline std::string describe_daemon_error(const std::string& name, const std::string& message) {
    using namespace haptics1::errors;
    static const std::map<std::string, std::string> kWords{
        {kInvalidDocument, "invalid"},
        {kOutOfRange, "out of range"},
        {kNotFound, "not found"},
        {kPermissionDenied, "not permitted"},
        {kLimitExceeded, "over a limit"},
        {kBusy, "busy"},
        {kDevice, "actuator failed"},
        {kNoAccelerometer, "no accelerometer"},
        {kUntrusted, "not trusted"},
        // A user cut off ([limits] max-on-time, StopAll) waits before repeating again.
        {kCoolingDown, "cooling down"},
    };
    if (const auto words = kWords.find(name); words != kWords.end()) {
        return words->second + ": " + message;
    }
    if (name.rfind(kErrorPrefix, 0) == 0) {
        return name + ": " + message;  // a newer daemon's error this client does not know
    }
    if (name == kServiceUnknown || name == kNameHasNoOwner) {
        return "vibscored is not running on the system bus (" + message + ")";
    }
    return message + " (" + name + ")";
}

}  // namespace vibscore::client
