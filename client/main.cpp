// vibscore: the command-line client. Offline verbs work on files without the daemon.
#include <CLI/CLI.hpp>

#include <iostream>

#include "client/bus_verbs.hpp"
#include "client/editor/editor_app.hpp"
#include "client/editor/verbs.hpp"
#include "client/offline_verbs.hpp"
#include "config.h"

using namespace vibscore::client;

int main(int argc, char** argv) {
    CLI::App app{
        "vibscore - compose, check and play vibrotactile scores.\n"
        "Exit status: 0 success, 1 invalid document or failed operation, 2 usage error.",
        "vibscore"};
    app.set_version_flag("--version", std::string("vibscore ") + VIBSCORE_VERSION);
    app.require_subcommand(1);

    std::vector<std::string> check_files;
    auto* check = app.add_subcommand(
        "check", "Validate scores (with the clefs they name) and clefs; list every problem.");
    check->add_option("FILE", check_files, "VibScore or VibClef documents")->required();

    RenderRequest render;
    auto* render_verb = app.add_subcommand(
        "render", "Render a score's drive signal (clef units) to CSV or WAV, or plot it.");
    render_verb->add_option("FILE", render.file, "VibScore document")->required();
    render_verb->add_option("--rate", render.rate, "samples per second (default 8000)")
        ->check(CLI::Range(1u, 384000u));
    render_verb->add_option("--out", render.out,
                            "OUT.csv (header t,y; one row per sample) or OUT.wav (32-bit float)");
    render_verb->add_flag("--plot", render.plot, "draw the strength over time in the terminal");
    render_verb->add_option("--width", render.plot_width, "plot width in columns (default 72)")
        ->check(CLI::Range(10, 1000));

    std::string info_file;
    auto* info = app.add_subcommand(
        "info",
        "Show a score's title, duration, bars and clefs, or a clef's mapping; for a registry "
        "score, also the clef each bar plays through on this device (asks vibscored).");
    info->add_option("FILE", info_file, "VibScore or VibClef document, or a registry score name")
        ->required();

    PlayRequest play_request;
    auto* play_verb = app.add_subcommand(
        "play", "Play a registry score, or a score file, on the device (through vibscored).");
    play_verb->add_option("SCORE", play_request.score, "registry name or VibScore file")
        ->required();
    play_verb->add_option("--usage", play_request.usage,
                          "ringtone, alarm, notification (default), communication, "
                          "accessibility, hardware-feedback, touch or media");
    play_verb->add_option("--repeat", play_request.repeat,
                          "0 once (default), n more times, -1 until stopped");
    play_verb->add_option("--clef", play_request.clef, "play every bar with this registry clef");
    play_verb->add_option("--intensity", play_request.intensity, "0..1")
        ->check(CLI::Range(0.0, 1.0));
    play_verb->add_flag("--wait", play_request.wait,
                        "stay until it ends, showing each bar; Ctrl-C stops it");

    std::uint64_t stop_id = 0;
    auto* stop_verb = app.add_subcommand("stop", "Stop a playback (default: all of yours).");
    stop_verb->add_option("ID", stop_id, "playback id printed by play");

    std::string kind = "score";
    std::string name;
    std::string file;
    auto* list_verb = app.add_subcommand("list", "List the registry's scores or clefs.");
    list_verb->add_option("KIND", kind, "scores (default) or clefs");
    auto* get_verb = app.add_subcommand("get", "Print a registry score or clef.");
    get_verb->add_option("KIND", kind, "score or clef")->required();
    get_verb->add_option("NAME", name, "registry name")->required();
    auto* compose_verb = app.add_subcommand(
        "compose", "Store a score or clef file in the registry (root or group vibscore).");
    compose_verb->add_option("NAME", name, "registry name")->required();
    compose_verb->add_option("FILE", file, "VibScore or VibClef file")->required();
    auto* delete_verb = app.add_subcommand("delete", "Delete a stored score or clef.");
    delete_verb->add_option("KIND", kind, "score or clef")->required();
    delete_verb->add_option("NAME", name, "registry name")->required();

    app.add_subcommand("drivers", "List the actuator backends vibscored offers (* in use).");
    std::string driver_name;
    auto* driver_verb =
        app.add_subcommand("driver",
                           "Show the actuator backend in use, or switch to another (root or group "
                           "vibscore; its settings come from vibscored.conf).");
    driver_verb->add_option("NAME", driver_name, "backend to switch to (see 'vibscore drivers')");

    vibscore::editor::ShowRequest show_request;
    auto* show_verb =
        app.add_subcommand("show", "Draw a registry score or a score file as staff notation.");
    show_verb->add_option("SCORE", show_request.score, "registry name or VibScore file")
        ->required();
    show_verb->add_option("--width", show_request.width, "columns (default: the terminal's)")
        ->check(CLI::Range(20, 10000));
    show_verb->add_flag("--colour,--color", show_request.colour,
                        "ANSI colours even when not writing to a terminal");

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

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "vibscore: " << e.what() << "\nRun 'vibscore --help' for usage.\n";
        return exit_usage;
    }

    if (check->parsed()) {
        return check_documents(check_files, std::cout, std::cerr);
    }
    if (render_verb->parsed()) {
        return render_document(render, std::cout, std::cerr);
    }
    if (play_verb->parsed()) {
        return play(play_request, std::cout, std::cerr);
    }
    if (stop_verb->parsed()) {
        return stop(stop_id, std::cout, std::cerr);
    }
    if (list_verb->parsed()) {
        return list(kind, std::cout, std::cerr);
    }
    if (get_verb->parsed()) {
        return get(kind, name, std::cout, std::cerr);
    }
    if (compose_verb->parsed()) {
        return compose(name, file, std::cout, std::cerr);
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
    if (show_verb->parsed()) {
        return vibscore::editor::show_score(show_request, std::cout, std::cerr);
    }
    if (edit_verb->parsed()) {
        return vibscore::editor::run_editor(edit_options, std::cerr);
    }
    if (is_document_file(info_file)) {
        return describe_document(info_file, std::cout, std::cerr);
    }
    return describe_registry_score(info_file, std::cout, std::cerr);
}
