#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include "actuator/declaration.hpp"
#include "client/clef_search.hpp"

namespace vibscore::client {

struct PlayRequest {
    std::string score;  // registry name, or a VibScore file (sent inline)
    std::string usage;
    int repeat = 0;
    std::string clef;
    double intensity = -1.0;  // < 0: not sent
    bool wait = false;
};

// The verbs that talk to vibscored on the system bus (DBUS_SYSTEM_BUS_ADDRESS may point
// elsewhere). Each returns an exit code and explains failures in plain words on err.
// A score file is loaded by the clef rule of ClefSearch, exactly as `check` loads it: clefs found
// as files are sent along with it, registry clefs go by name.
int play(const PlayRequest& request, const ClefSearch& clefs, std::ostream& out, std::ostream& err);
int stop(std::uint64_t id, std::ostream& out, std::ostream& err);
// Every playback, whoever started it (StopAll: polkit org.vibscore.manage).
int stop_all(std::ostream& out, std::ostream& err);
int list(const std::string& kind, std::ostream& out, std::ostream& err);
// --device: a clef as this device plays it ([clefs] maps it, or fit = auto fits it to the
// declared actuator), as vibscored binds it.
int get(const std::string& kind, const std::string& name, std::ostream& out, std::ostream& err,
        bool device = false);
// A score's clefs must be registry clefs in the store: each href that names a clef file is
// rewritten to the registry clef of the same name when that clef is the same, else refused.
int compose(const std::string& name, const std::string& file, const ClefSearch& clefs,
            std::ostream& out, std::ostream& err);
int remove(const std::string& kind, const std::string& name, std::ostream& out, std::ostream& err);
// vibscore info NAME: a registry score as the daemon holds it, the clef each bar plays through
// on this device (the daemon's [clefs] map) and the actuator it plays on.
int describe_registry_score(const std::string& name, std::ostream& out, std::ostream& err);
// The actuator vibscored declares ([actuator], its Actuator property): for `--actuator` given
// without a file. Throws std::runtime_error saying why when the daemon cannot be asked or
// declares none.
actuator::Declaration daemon_actuator();
// The actuator backends the daemon offers, with the one in use marked.
int list_drivers(std::ostream& out, std::ostream& err);
// Without a name: the driver in use, its capabilities and the declared actuator. With one:
// switch to it.
int driver(const std::string& name, std::ostream& out, std::ostream& err);

// For ClefSearch::registry: asks vibscored for registry clef NAME (within a second or two);
// nullopt when it has none or is not there.
std::function<std::optional<std::string>(const std::string& name)> registry_clef_fetcher();

}  // namespace vibscore::client
