#pragma once

#include <cstdint>
#include <ostream>
#include <string>

namespace vibscore::client {

struct PlayRequest {
    std::string score;  // registry name, or a VibScore file (sent inline)
    std::string usage;
    int repeat = 0;
    std::string clef;
    double intensity = -1.0;  // < 0: not sent
    bool wait = false;
};

// A score argument that is a file rather than a registry name: it has a '/' or names a regular
// file in the working directory.
bool is_document_file(const std::string& argument);

// The verbs that talk to vibscored on the system bus (DBUS_SYSTEM_BUS_ADDRESS may point
// elsewhere). Each returns an exit code and explains failures in plain words on err.
int play(const PlayRequest& request, std::ostream& out, std::ostream& err);
int stop(std::uint64_t id, std::ostream& out, std::ostream& err);
int list(const std::string& kind, std::ostream& out, std::ostream& err);
int get(const std::string& kind, const std::string& name, std::ostream& out, std::ostream& err);
int compose(const std::string& name, const std::string& file, std::ostream& out, std::ostream& err);
int remove(const std::string& kind, const std::string& name, std::ostream& out, std::ostream& err);
// vibscore info NAME: a registry score as the daemon holds it, and the clef each bar plays
// through on this device (the daemon's [clefs] map).
int describe_registry_score(const std::string& name, std::ostream& out, std::ostream& err);
// The actuator backends the daemon offers, with the one in use marked.
int list_drivers(std::ostream& out, std::ostream& err);
// Without a name: the driver in use and its capabilities. With one: switch to it.
int driver(const std::string& name, std::ostream& out, std::ostream& err);

}  // namespace vibscore::client
