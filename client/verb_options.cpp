#include "client/verb_options.hpp"

#include "client/actuator_option.hpp"
#include "client/bus_verbs.hpp"
#include "client/offline_verbs.hpp"

namespace vibscore::client {

CLI::Validator kind_validator() {
    return CLI::IsMember({"score", "scores", "clef", "clefs"});
}

void add_clefs_option(CLI::App& verb, ClefSearch& search) {
    verb.add_option("--clefs", search.folders,
                    "folder of NAME.clef.xml files where a clef the score names by registry "
                    "name is looked up first (repeatable; then vibscored, then the shipped clefs)")
        ->check(CLI::ExistingDirectory);
}

void add_actuator_option(CLI::App& verb, std::string& spec, const std::string& what) {
    verb.add_option("--actuator", spec,
                    "the actuator declared in FILE's [actuator] section (vibscored.conf will "
                    "do), or without FILE the one vibscored declares: " +
                        what)
        ->expected(0, 1)
        ->default_str(kDaemonActuator)
        ->type_name("[FILE]");
}

int resolve_actuator(const std::string& spec, std::optional<actuator::Declaration>& declared,
                     std::ostream& err) {
    if (spec.empty()) {
        return exit_ok;
    }
    const bool daemon = spec == kDaemonActuator;
    try {
        declared = daemon ? daemon_actuator() : load_actuator(spec);
        return exit_ok;
    } catch (const ActuatorFileUnreadable& error) {
        err << "vibscore: " << error.what() << "\n";
        return exit_failed;
    } catch (const std::exception& error) {
        err << "vibscore: " << error.what() << "\n";
        return daemon ? exit_failed : exit_usage;
    }
}

}  // namespace vibscore::client
