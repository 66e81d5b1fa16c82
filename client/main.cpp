// vibscore: the command-line client. Offline verbs work on files without the daemon.
#include <CLI/CLI.hpp>

#include <iostream>
#include <iterator>
#include <limits>

#include "client/actuator_option.hpp"
#include "client/assign_verb.hpp"
#include "client/bus_verbs.hpp"
#include "client/calibrate_live.hpp"
#include "client/calibrate_verb.hpp"
#include "client/clef_verbs.hpp"
#include "client/convert_verb.hpp"
#include "client/daemon_documents.hpp"
#include "client/editor/documents.hpp"
#include "client/editor/editor_app.hpp"
#include "client/editor/verbs.hpp"
#include "client/number_options.hpp"
#include "client/offline_verbs.hpp"
#include "client/picture_verbs.hpp"
#include "common/closest_name.hpp"
#include "config.h"

using namespace vibscore::client;

namespace {

constexpr const char* kUsages[] = {"ringtone",      "alarm",         "notification",
                                   "communication", "accessibility", "hardware-feedback",
                                   "touch",         "media"};
constexpr const char* kKindHelp = "score or clef (scores and clefs work too)";
// What `--actuator` without a file stands for: ask vibscored.
constexpr const char* kDaemonActuator = "daemon";

// Registry kinds, the plural too, as vibscored takes them.
CLI::Validator kind_validator() {
    return CLI::IsMember({"score", "scores", "clef", "clefs"});
}

// `--clefs DIR` (repeatable) on the verbs that load score files: where registry clef names are
// looked up first (docs/score-format.md).
void add_clefs_option(CLI::App* verb, ClefSearch& search) {
    verb->add_option("--clefs", search.folders,
                     "folder of NAME.clef.xml files where a clef the score names by registry "
                     "name is looked up first (repeatable; then vibscored, then the shipped clefs)")
        ->check(CLI::ExistingDirectory);
}

// `--actuator [FILE]` on the verbs that show what an actuator makes of a score: a file with an
// [actuator] section (vibscored.conf will do), or without one the daemon's declaration.
void add_actuator_option(CLI::App* verb, std::string& spec, const std::string& what) {
    verb->add_option("--actuator", spec,
                     "the actuator declared in FILE's [actuator] section (vibscored.conf will "
                     "do), or without FILE the one vibscored declares: " +
                         what)
        ->expected(0, 1)
        ->default_str(kDaemonActuator)
        ->type_name("[FILE]");
}

// The declaration `--actuator` names, into `declared` (nothing when not given). exit_ok, or,
// having said why there is none, exit_usage for a bad file and exit_failed when vibscored could
// not give one.
int resolve_actuator(const std::string& spec,
                     std::optional<vibscore::actuator::Declaration>& declared, std::ostream& err) {
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

// "unknown command "x"" with the commands, instead of CLI11's "arguments were not expected".
std::string unknown_verb_message(const CLI::App& app, const std::string& word) {
    std::vector<std::string> verbs;
    for (const auto* verb : app.get_subcommands({})) {
        verbs.push_back(verb->get_name());
    }
    std::string message = "unknown command \"" + word + "\"";
    if (const auto meant = vibscore::closest_name(word, verbs)) {
        message += " (did you mean " + *meant + "?)";
    }
    message += "; the commands are:";
    for (const auto& verb : verbs) {
        message += " " + verb;
    }
    return message;
}

// CLI11 says only "A subcommand is required" both when no verb is given and when the verb is
// misspelt; name the word instead.
std::string usage_error_message(const CLI::App& app, const CLI::ParseError& error) {
    const auto extras = app.remaining();
    if (!app.get_subcommands().empty()) {
        return error.what();
    }
    if (extras.empty()) {
        return "a command is required (see --help for the commands)";
    }
    if (extras.front().starts_with("-")) {
        return "unknown option " + extras.front();
    }
    return unknown_verb_message(app, extras.front());
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "vibscore - compose, check and play vibrotactile scores.\n"
        "Exit status: 0 success, 1 invalid document or failed operation, 2 usage error.\n"
        "The docs/NAME.md below are in " VIBSCORE_CLIENT_DOCDIR " once installed; man vibscore.",
        "vibscore"};
    app.set_version_flag("--version", std::string("vibscore ") + VIBSCORE_VERSION);
    app.require_subcommand(1);

    ClefSearch clef_search;
    clef_search.registry = registry_clef_fetcher();
    clef_search.registry_score = registry_score_fetcher();

    std::vector<std::string> check_files;
    auto* check = app.add_subcommand(
        "check", "Validate scores (with the clefs they name) and clefs; list every problem.");
    check
        ->add_option("FILE", check_files,
                     "VibScore or VibClef files, or registry score or clef names")
        ->required();
    add_clefs_option(check, clef_search);
    std::string check_actuator;
    add_actuator_option(check, check_actuator,
                        "also warn, naming bar, note and numbers, where a score asks what the "
                        "actuator cannot give; without FILE through the clefs vibscored plays "
                        "it with (mapped or fitted, as get clef NAME --device gives them)");

    RenderRequest render;
    auto* render_verb = app.add_subcommand(
        "render", "Render a score's drive signal (clef units) to CSV or WAV, or plot it.");
    render_verb->add_option("FILE", render.file, "VibScore file or registry score name")
        ->required();
    render_verb->add_option("--rate", render.rate, "samples per second (default 8000)")
        ->check(number_between(1, 384000, NumberKind::whole));
    render_verb->add_option("--out", render.out,
                            "OUT.csv (header t,y; one row per sample) or OUT.wav (32-bit float)");
    render_verb->add_flag("--plot", render.plot, "draw the strength over time in the terminal");
    render_verb->add_option("--width", render.plot_width, "plot width in columns (default 72)")
        ->check(number_between(10, 1000, NumberKind::whole));
    add_clefs_option(render_verb, clef_search);
    render_verb->add_option("--svg", render.svg,
                            "draw the signal and its envelope, with bar and note boundaries, "
                            "as an SVG picture");
    render_verb->add_option("--png", render.png, "the same picture as a PNG image");
    std::string render_actuator;
    add_actuator_option(render_verb, render_actuator,
                        "--out FILE.csv then has t,written,uncompensated,compensated: the "
                        "strength written and what the actuator produces without and with "
                        "compensation; --plot, --svg and --png draw those three; without FILE "
                        "the score plays through the clefs vibscored uses (mapped or fitted, as "
                        "get clef NAME --device gives them), which the picture names");

    ConvertRequest convert_request;
    auto* convert_verb = app.add_subcommand(
        "convert",
        "Convert a score to AHAP, Android JSON or XML, or MIDI; or AHAP, Android, RTTTL or MIDI "
        "to a score (docs/formats.md says what each format keeps).");
    convert_verb->add_option("IN", convert_request.in, "file to read")->required();
    convert_verb->add_option("OUT", convert_request.out, "file to write")->required();
    convert_verb->add_option("--from", convert_request.from,
                             "format of IN when its name does not tell: score, ahap, "
                             "android-json, android-xml, rtttl, midi");
    convert_verb->add_option("--to", convert_request.to,
                             "format of OUT when its name does not tell: score, ahap, "
                             "android-json, android-xml, android-envelope, midi");
    convert_verb->add_option("--clef", convert_request.clef,
                             "clef an import is written on: a clef file, or a clef's name found "
                             "as check finds one (--clefs, vibscored, the shipped clefs; "
                             "default lra-phone)");
    add_clefs_option(convert_verb, clef_search);
    convert_verb
        ->add_option("--track", convert_request.track,
                     "MIDI track to import, from 1 (default: the first with notes)")
        ->check(number_between(1, 65535, NumberKind::whole));
    convert_verb->add_flag("--loop", convert_request.loop,
                           "Android: the pattern repeats (repeat index 0, <repeating>)");

    auto* clef_verb = app.add_subcommand("clef", "Work on clefs: fit one to the actuator.");
    clef_verb->require_subcommand(1);
    ClefFitRequest clef_fit;
    std::string clef_fit_actuator = kDaemonActuator;
    auto* clef_fit_verb = clef_verb->add_subcommand(
        "fit",
        "Write a device clef for the declared actuator from a written clef: strings where it "
        "plays them at full strength (or roughness), numbers keeping their strengths, shapes it "
        "cannot follow smoothed (docs/clefs.md). What changed goes to standard error.");
    clef_fit_verb->add_option("CLEF", clef_fit.clef, "VibClef file or registry clef name")
        ->required();
    clef_fit_verb
        ->add_option("--actuator", clef_fit_actuator,
                     "the actuator declared in FILE's [actuator] section (vibscored.conf will "
                     "do), or 'daemon' (the default): the one vibscored declares")
        ->type_name("FILE|daemon");
    clef_fit_verb
        ->add_option("-o,--output", clef_fit.output,
                     "write the fitted clef to OUT (default: standard output)")
        ->type_name("OUT");
    add_clefs_option(clef_fit_verb, clef_search);

    std::string info_file;
    auto* info = app.add_subcommand(
        "info",
        "Show a score's title, duration, bars and clefs, or a clef's mapping; for a registry "
        "score, also the clef each bar plays through on this device (asks vibscored).");
    info->add_option("SCORE", info_file,
                     "registry score name, or a VibScore or VibClef file (a name with a / or "
                     "ending in .xml, or a file that exists)")
        ->required();
    add_clefs_option(info, clef_search);

    PlayRequest play_request;
    auto* play_verb = app.add_subcommand(
        "play", "Play a registry score, or a score file, on the device (through vibscored).");
    play_verb->add_option("SCORE", play_request.score, "registry name or VibScore file")
        ->required();
    play_verb
        ->add_option("--usage", play_request.usage,
                     "ringtone, alarm, notification (default), communication, "
                     "accessibility, hardware-feedback, touch or media")
        ->check(CLI::IsMember(std::vector<std::string>(std::begin(kUsages), std::end(kUsages))));
    play_verb
        ->add_option("--repeat", play_request.repeat,
                     "0 once (default), n more times, -1 until stopped")
        ->check(number_between(-1, std::numeric_limits<int>::max(), NumberKind::whole));
    play_verb->add_option("--clef", play_request.clef, "play every bar with this registry clef");
    play_verb->add_option("--intensity", play_request.intensity, "0..1")
        ->check(number_between(0, 1));
    add_clefs_option(play_verb, clef_search);
    play_verb->add_flag("--wait", play_request.wait,
                        "stay until it ends, showing each bar; Ctrl-C stops it");

    std::uint64_t stop_id = 0;
    bool stop_everyone = false;
    auto* stop_verb = app.add_subcommand("stop", "Stop a playback (default: all of yours).");
    auto* stop_id_option =
        stop_verb->add_option("ID", stop_id, "playback id printed by play")
            ->check(number_between(1, std::numeric_limits<double>::infinity(), NumberKind::whole));
    stop_verb
        ->add_flag("--all", stop_everyone,
                   "every playback, whoever started it (polkit: org.vibscore.manage)")
        ->excludes(stop_id_option);

    std::string kind = "score";
    std::string name;
    std::string file;
    auto* list_verb = app.add_subcommand("list", "List the registry's scores or clefs.");
    list_verb->add_option("KIND", kind, std::string(kKindHelp) + "; default score")
        ->check(kind_validator());
    auto* get_verb = app.add_subcommand("get", "Print a registry score or clef.");
    get_verb->add_option("KIND", kind, kKindHelp)->required()->check(kind_validator());
    get_verb->add_option("NAME", name, "registry name")->required();
    bool get_device = false;
    get_verb->add_flag("--device", get_device,
                       "a clef as this device plays it: the clef [clefs] maps it to, or fitted to "
                       "the declared actuator (fit = auto)");
    auto* compose_verb = app.add_subcommand(
        "compose",
        "Store a score or clef file in the registry (polkit: org.vibscore.compose; without "
        "polkit, root and group vibscore).");
    compose_verb->add_option("NAME", name, "registry name")->required();
    compose_verb->add_option("FILE", file, "VibScore or VibClef file")->required();
    add_clefs_option(compose_verb, clef_search);
    auto* delete_verb = app.add_subcommand(
        "delete", "Delete a stored score or clef (polkit: org.vibscore.compose).");
    delete_verb->add_option("KIND", kind, kKindHelp)->required()->check(kind_validator());
    delete_verb->add_option("NAME", name, "registry name")->required();

    app.add_subcommand("drivers", "List the actuator backends vibscored offers (* in use).");
    std::string driver_name;
    auto* driver_verb =
        app.add_subcommand("driver",
                           "Show the actuator backend in use and why (driver = auto: what it "
                           "found), or switch to another (polkit: org.vibscore.manage; without "
                           "polkit, root and group vibscore; its settings come from "
                           "vibscored.conf).");
    driver_verb->add_option("NAME", driver_name, "backend to switch to (see 'vibscore drivers')");

    vibscore::editor::ShowRequest show_request;
    auto* show_verb = app.add_subcommand(
        "show",
        "Draw a registry score or a score file as staff notation; with --svg or --png, a clef's "
        "strings and numbers too.");
    show_verb
        ->add_option("SCORE", show_request.score,
                     "registry name or VibScore file (with --svg/--png: or a clef, by file "
                     "or name)")
        ->required();
    show_verb->add_option("--width", show_request.width, "columns (default: the terminal's)")
        ->check(number_between(20, 10000, NumberKind::whole));
    show_verb->add_flag("--colour,--color", show_request.colour,
                        "ANSI colours even when not writing to a terminal");
    std::string show_svg, show_png;
    show_verb->add_option("--svg", show_svg,
                          "draw the staff (or the clef) as an SVG picture instead");
    show_verb->add_option("--png", show_png, "draw the staff (or the clef) as a PNG image instead");
    add_clefs_option(show_verb, clef_search);
    std::string show_actuator;
    add_actuator_option(show_verb, show_actuator,
                        "with --svg/--png, a clef is drawn over the actuator's response (an LRA's "
                        "strength at full drive over frequency, and what each number reaches on "
                        "each string)");

    AssignRequest assign_request;
    auto* assign_verb = app.add_subcommand(
        "assign",
        "Choose the registry score a feedback event plays for you (vibscore-feedback; "
        "docs/feedbackd.md): EVENT SCORE, EVENT --default, or --list.");
    assign_verb->add_option("EVENT", assign_request.event, "event name, e.g. phone-incoming-call");
    assign_verb->add_option("SCORE", assign_request.score, "registry score to play for it");
    assign_verb->add_flag("--default", assign_request.to_default,
                          "play the theme's score for EVENT again");
    assign_verb->add_flag("--list", assign_request.list,
                          "list the events and the score each plays");
    assign_verb->add_flag("--force", assign_request.force,
                          "assign an event the theme does not know (yet); its name must still "
                          "be lower-case words and hyphens, at most 64 characters");

    CalibrateRequest calibrate_request;
    auto* calibrate_verb = app.add_subcommand(
        "calibrate",
        "Measure the actuator with the device's accelerometer: vibscored plays a short probe "
        "and estimates the [actuator] numbers (--apply: use them from now on; polkit: "
        "org.vibscore.manage). Offline, for any recorder: --plan writes the probe, --estimate "
        "reads a recording of it. Exit 1 when the estimate is not trusted.");
    calibrate_verb->add_flag("--apply", calibrate_request.apply,
                             "live: make a trusted estimate the numbers in use, kept across "
                             "restarts (the configuration file is left as it is)");
    auto* calibrate_plan_flag = calibrate_verb->add_flag(
        "--plan", calibrate_request.plan,
        "write the probe as a drive trace (time_ns,amplitude,frequency_hz) to -o FILE");
    auto* calibrate_estimate_option =
        calibrate_verb
            ->add_option("--estimate", calibrate_request.estimate,
                         "estimate from PLAN.csv and a recording of it, ACCEL.csv (t,x,y,z: "
                         "seconds from the plan's first row, m/s\u00b2)")
            ->expected(2)
            ->type_name("PLAN.csv ACCEL.csv");
    calibrate_plan_flag->excludes(calibrate_estimate_option);
    calibrate_verb->add_option("--kind", calibrate_request.kind, "erm or lra (offline)")
        ->check(CLI::IsMember({"erm", "lra"}));
    calibrate_verb
        ->add_option("--actuator", calibrate_request.actuator_file,
                     "offline: the nominal declaration, FILE's [actuator] section (vibscored.conf "
                     "will do): the kind, and the numbers shown beside the measured ones")
        ->type_name("FILE");
    calibrate_verb->add_option("-o,--output", calibrate_request.output,
                               "--plan: the file to write (default: standard output)");
    calibrate_verb->add_option("--png", calibrate_request.png,
                               "draw the recording over the model with the measured numbers "
                               "(solid) and the declared ones (dashed) as a PNG image");
    calibrate_verb->add_option("--svg", calibrate_request.svg, "the same picture as SVG");

    vibscore::editor::EditOptions edit_options;
    auto* edit_verb = app.add_subcommand(
        "edit", "Compose in the terminal, by keyboard or six buttons (docs/editor.md).");
    edit_verb->add_option("SCORE", edit_options.target,
                          "registry name or VibScore file (default: a new score)");
    edit_verb->add_option("--clef", edit_options.clef,
                          "a new score's clef: registry clef or clef file (default lra-phone)");
    edit_verb->add_option("--buttons", edit_options.buttons,
                          "evdev device whose keys are the six buttons (repeatable)");
    edit_verb->add_option("--keymap,--button-map", edit_options.button_map,
                          "keys for the buttons, e.g. up=KEY_UP,select=KEY_ENTER,back=long:KEY_"
                          "POWER (default: phone volume and power keys)");
    edit_verb->add_flag("--grab", edit_options.grab,
                        "take the button devices' keys for the editor alone");
    edit_verb->footer(
        "Six buttons (Up Down Left Right Select Back; arrows, Enter, Escape on a keyboard):\n"
        "  the status line names what each does now. Back gives the other choices,\n"
        "  Back, Select the menu: tap a rhythm (t), bar clef (k), edit clefs (K: a clef's\n"
        "  frequencies, amplitudes, tempo and points, heard as they change, saved under a\n"
        "  new name), save, save as. Saving a new score first asks 'use for ...': an event\n"
        "  of the feedback theme (incoming call, new message, ...) then plays it for this\n"
        "  user (as 'vibscore assign' does).\n"
        "Keys: 1-9 note, 0 rest, Space play, Ctrl+S save, Ctrl+Z undo, q quit.");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "vibscore: " << usage_error_message(app, e)
                  << "\nRun 'vibscore --help' for usage.\n";
        return exit_usage;
    }

    if (check->parsed()) {
        std::optional<vibscore::actuator::Declaration> declared;
        if (const int failed = resolve_actuator(check_actuator, declared, std::cerr)) {
            return failed;
        }
        return check_documents(
            check_files, clef_search, std::cout, std::cerr, declared,
            check_actuator == kDaemonActuator ? daemon_clef_binder() : DeviceClefBinder{});
    }
    if (render_verb->parsed()) {
        if (const int failed = resolve_actuator(render_actuator, render.actuator, std::cerr)) {
            return failed;
        }
        if (render_actuator == kDaemonActuator) {
            render.device_clefs = daemon_clef_binder();
        }
        return render_document(render, clef_search, std::cout, std::cerr);
    }
    if (clef_fit_verb->parsed()) {
        std::optional<vibscore::actuator::Declaration> declared;
        // A fit needs an actuator: an empty name is not "none given" here (the default is the
        // daemon's), and reading on without one would use a declaration that is not there.
        if (clef_fit_actuator.empty()) {
            std::cerr << "vibscore: clef fit: --actuator needs a file or 'daemon', not an empty "
                         "name\n";
            return exit_usage;
        }
        if (const int failed = resolve_actuator(clef_fit_actuator, declared, std::cerr)) {
            return failed;
        }
        clef_fit.actuator = *declared;
        return fit_clef_document(clef_fit, clef_search, std::cout, std::cerr);
    }
    if (convert_verb->parsed()) {
        return convert(convert_request, clef_search, std::cout, std::cerr);
    }
    if (play_verb->parsed()) {
        return play(play_request, clef_search, std::cout, std::cerr);
    }
    if (stop_verb->parsed()) {
        return stop_everyone ? stop_all(std::cout, std::cerr) : stop(stop_id, std::cout, std::cerr);
    }
    if (list_verb->parsed()) {
        return list(kind, std::cout, std::cerr);
    }
    if (get_verb->parsed()) {
        return get(kind, name, std::cout, std::cerr, get_device);
    }
    if (compose_verb->parsed()) {
        return compose(name, file, clef_search, std::cout, std::cerr);
    }
    if (delete_verb->parsed()) {
        return remove(kind, name, std::cout, std::cerr);
    }
    if (app.got_subcommand("drivers")) {
        return list_drivers(std::cout, std::cerr);
    }
    if (driver_verb->parsed()) {
        return driver(driver_name, std::cout, std::cerr);
    }
    if (show_verb->parsed() && (!show_svg.empty() || !show_png.empty())) {
        std::optional<vibscore::actuator::Declaration> declared;
        if (const int failed = resolve_actuator(show_actuator, declared, std::cerr)) {
            return failed;
        }
        return show_picture(show_request.score, show_svg, show_png, clef_search, std::cout,
                            std::cerr, declared);
    }
    if (show_verb->parsed() && !show_actuator.empty()) {
        std::cerr << "vibscore: show --actuator draws a picture: give --svg FILE or --png FILE\n";
        return exit_usage;
    }
    if (show_verb->parsed()) {
        return vibscore::editor::show_score(show_request, std::cout, std::cerr);
    }
    if (calibrate_verb->parsed()) {
        if (calibrate_request.plan) {
            return calibrate_plan(calibrate_request, std::cout, std::cerr);
        }
        if (!calibrate_request.estimate.empty()) {
            return calibrate_estimate(calibrate_request, std::cout, std::cerr);
        }
        return calibrate_live(calibrate_request, std::cout, std::cerr);
    }
    if (assign_verb->parsed()) {
        return assign(assign_request, std::cout, std::cerr);
    }
    if (edit_verb->parsed()) {
        return vibscore::editor::run_editor(edit_options, std::cerr);
    }
    // The same rule as play and show: a path, or else a registry name.
    if (vibscore::editor::classify_source(info_file).kind ==
        vibscore::editor::ScoreSource::Kind::registry) {
        return describe_registry_score(info_file, std::cout, std::cerr);
    }
    return describe_document(info_file, clef_search, std::cout, std::cerr);
}
