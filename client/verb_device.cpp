// The verbs on vibscored, its registry and the device: play, stop, list, get, compose, delete,
// drivers, driver, assign and calibrate. Each declares its arguments and options bound to a state
// its handler owns.
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>

#include "client/assign_verb.hpp"
#include "client/bus_verbs.hpp"
#include "client/calibrate_live.hpp"
#include "client/calibrate_verb.hpp"
#include "client/number_options.hpp"
#include "client/verb_declare.hpp"
#include "client/verb_options.hpp"

namespace vibscore::client {

namespace {

constexpr const char* kUsages[] = {"ringtone",      "alarm",         "notification",
                                   "communication", "accessibility", "hardware-feedback",
                                   "touch",         "media"};

// KIND and NAME of a registry entry (get, delete).
struct Entry {
    std::string kind = "score";
    std::string name;
};

std::shared_ptr<Entry> add_entry(CLI::App& command) {
    auto entry = std::make_shared<Entry>();
    command.add_option("KIND", entry->kind, kKindHelp)->required()->check(kind_validator());
    command.add_option("NAME", entry->name, "registry name")->required();
    return entry;
}

}  // namespace

VerbHandler declare_play(CLI::App& command, VerbContext& context) {
    auto request = std::make_shared<PlayRequest>();
    command.add_option("SCORE", request->score, "registry name or VibScore file")->required();
    command
        .add_option("--usage", request->usage,
                    "ringtone, alarm, notification (default), communication, "
                    "accessibility, hardware-feedback, touch or media")
        ->check(CLI::IsMember(std::vector<std::string>(std::begin(kUsages), std::end(kUsages))));
    command
        .add_option("--repeat", request->repeat, "0 once (default), n more times, -1 until stopped")
        ->check(number_between(-1, std::numeric_limits<int>::max(), NumberKind::whole));
    command.add_option("--clef", request->clef, "play every bar with this registry clef");
    command.add_option("--intensity", request->intensity, "0..1")->check(number_between(0, 1));
    add_clefs_option(command, context.clef_search);
    command.add_flag("--wait", request->wait,
                     "stay until it ends, showing each bar; Ctrl-C stops it");
    return
        [request, &context] { return play(*request, context.clef_search, std::cout, std::cerr); };
}

VerbHandler declare_stop(CLI::App& command, VerbContext&) {
    struct State {
        std::uint64_t id = 0;
        bool everyone = false;
    };
    auto state = std::make_shared<State>();
    auto* id =
        command.add_option("ID", state->id, "playback id printed by play")
            ->check(number_between(1, std::numeric_limits<double>::infinity(), NumberKind::whole));
    command
        .add_flag("--all", state->everyone,
                  "every playback, whoever started it (polkit: org.vibscore.manage)")
        ->excludes(id);
    return [state] {
        return state->everyone ? stop_all(std::cout, std::cerr)
                               : stop(state->id, std::cout, std::cerr);
    };
}

VerbHandler declare_list(CLI::App& command, VerbContext&) {
    auto kind = std::make_shared<std::string>("score");
    command.add_option("KIND", *kind, std::string(kKindHelp) + "; default score")
        ->check(kind_validator());
    return [kind] { return list(*kind, std::cout, std::cerr); };
}

VerbHandler declare_get(CLI::App& command, VerbContext&) {
    auto entry = add_entry(command);
    auto device = std::make_shared<bool>(false);
    command.add_flag("--device", *device,
                     "a clef as this device plays it: the clef [clefs] maps it to, or fitted to "
                     "the declared actuator (fit = auto)");
    return [entry, device] { return get(entry->kind, entry->name, std::cout, std::cerr, *device); };
}

VerbHandler declare_compose(CLI::App& command, VerbContext& context) {
    struct State {
        std::string name, file;
    };
    auto state = std::make_shared<State>();
    command.add_option("NAME", state->name, "registry name")->required();
    command.add_option("FILE", state->file, "VibScore or VibClef file")->required();
    add_clefs_option(command, context.clef_search);
    return [state, &context] {
        return compose(state->name, state->file, context.clef_search, std::cout, std::cerr);
    };
}

VerbHandler declare_delete(CLI::App& command, VerbContext&) {
    auto entry = add_entry(command);
    return [entry] { return remove(entry->kind, entry->name, std::cout, std::cerr); };
}

VerbHandler declare_drivers(CLI::App&, VerbContext&) {
    return [] { return list_drivers(std::cout, std::cerr); };
}

VerbHandler declare_driver(CLI::App& command, VerbContext&) {
    auto name = std::make_shared<std::string>();
    command.add_option("NAME", *name, "backend to switch to (see 'vibscore drivers')");
    return [name] { return driver(*name, std::cout, std::cerr); };
}

VerbHandler declare_assign(CLI::App& command, VerbContext&) {
    auto request = std::make_shared<AssignRequest>();
    command.add_option("EVENT", request->event, "event name, e.g. phone-incoming-call");
    command.add_option("SCORE", request->score, "registry score to play for it");
    command.add_flag("--default", request->to_default, "play the theme's score for EVENT again");
    command.add_flag("--list", request->list, "list the events and the score each plays");
    command.add_flag("--force", request->force,
                     "assign an event the theme does not know (yet); its name must still "
                     "be lower-case words and hyphens, at most 64 characters");
    return [request] { return assign(*request, std::cout, std::cerr); };
}

VerbHandler declare_calibrate(CLI::App& command, VerbContext&) {
    auto request = std::make_shared<CalibrateRequest>();
    command.add_flag("--apply", request->apply,
                     "live: make a trusted estimate the numbers in use, kept across "
                     "restarts (the configuration file is left as it is)");
    auto* plan = command.add_flag(
        "--plan", request->plan,
        "write the probe as a drive trace (time_ns,amplitude,frequency_hz) to -o FILE");
    auto* estimate = command
                         .add_option("--estimate", request->estimate,
                                     "estimate from PLAN.csv and a recording of it, ACCEL.csv "
                                     "(t,x,y,z: seconds from the plan's first row, m/s\u00b2)")
                         ->expected(2)
                         ->type_name("PLAN.csv ACCEL.csv");
    plan->excludes(estimate);
    command.add_option("--kind", request->kind, "erm or lra (offline)")
        ->check(CLI::IsMember({"erm", "lra"}));
    command
        .add_option("--actuator", request->actuator_file,
                    "offline: the nominal declaration, FILE's [actuator] section (vibscored.conf "
                    "will do): the kind, and the numbers shown beside the measured ones")
        ->type_name("FILE");
    command.add_option("-o,--output", request->output,
                       "--plan: the file to write (default: standard output)");
    command.add_option("--png", request->png,
                       "draw the recording over the model with the measured numbers "
                       "(solid) and the declared ones (dashed) as a PNG image");
    command.add_option("--svg", request->svg, "the same picture as SVG");
    return [request] {
        if (request->plan) {
            return calibrate_plan(*request, std::cout, std::cerr);
        }
        if (!request->estimate.empty()) {
            return calibrate_estimate(*request, std::cout, std::cerr);
        }
        return calibrate_live(*request, std::cout, std::cerr);
    };
}

}  // namespace vibscore::client
