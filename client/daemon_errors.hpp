#pragma once

#include <map>
#include <string>

namespace vibscore::client {

// A D-Bus error from vibscored in plain words, for people: its named errors become
// "not found: <message>", "not permitted: <message>" and so on; a daemon that is not there
// says so. Shared by the command-line verbs and the editor's status line.
inline std::string describe_daemon_error(const std::string& name, const std::string& message) {
    const std::string prefix = "org.vibscore.Haptics1.Error.";
    if (name.rfind(prefix, 0) == 0) {
        static const std::map<std::string, std::string> kWords{
            {"InvalidDocument", "invalid"},
            {"NotFound", "not found"},
            {"PermissionDenied", "not permitted"},
            {"LimitExceeded", "over a limit"},
            {"Busy", "busy"},
            {"Device", "actuator failed"},
        };
        const auto words = kWords.find(name.substr(prefix.size()));
        return (words == kWords.end() ? name : words->second) + ": " + message;
    }
    if (name == "org.freedesktop.DBus.Error.ServiceUnknown" ||
        name == "org.freedesktop.DBus.Error.NameHasNoOwner") {
        return "vibscored is not running on the system bus (" + message + ")";
    }
    return message + " (" + name + ")";
}

}  // namespace vibscore::client
