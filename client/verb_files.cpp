// The verbs on documents: check, render, convert, clef fit, info, show and edit. Each declares
// its arguments and options bound to a state its handler owns.
#include <iostream>
#include <memory>

#include "client/bus_verbs.hpp"
#include "client/clef_verbs.hpp"
#include "client/convert_verb.hpp"
#include "client/daemon_documents.hpp"
#include "client/editor/documents.hpp"
#include "client/editor/editor_app.hpp"
#include "client/editor/verbs.hpp"
#include "client/number_options.hpp"
#include "client/offline_verbs.hpp"
#include "client/picture_verbs.hpp"
#include "client/verb_declare.hpp"
#include "client/verb_options.hpp"

namespace vibscore::client {

VerbHandler declare_check(CLI::App& command, VerbContext& context) {
    struct State {
        std::vector<std::string> files;
        std::string actuator;
    };
    auto state = std::make_shared<State>();
    command
        .add_option("FILE", state->files,
                    "VibScore or VibClef files, or registry score or clef names")
        ->required();
    add_clefs_option(command, context.clef_search);
    add_actuator_option(command, state->actuator,
                        "also warn, naming bar, note and numbers, where a score asks what the "
                        "actuator cannot give; without FILE through the clefs vibscored plays "
                        "it with (mapped or fitted, as get clef NAME --device gives them)");
    return [state, &context] {
        std::optional<actuator::Declaration> declared;
        if (const int failed = resolve_actuator(state->actuator, declared, std::cerr)) {
            return failed;
        }
        return check_documents(
            state->files, context.clef_search, std::cout, std::cerr, declared,
            state->actuator == kDaemonActuator ? daemon_clef_binder() : DeviceClefBinder{});
    };
}

VerbHandler declare_render(CLI::App& command, VerbContext& context) {
    struct State {
        RenderRequest request;
        std::string actuator;
    };
    auto state = std::make_shared<State>();
    RenderRequest& render = state->request;
    command.add_option("FILE", render.file, "VibScore file or registry score name")->required();
    command.add_option("--rate", render.rate, "samples per second (default 8000)")
        ->check(number_between(1, 384000, NumberKind::whole));
    command.add_option("--out", render.out,
                       "OUT.csv (header t,y; one row per sample) or OUT.wav (32-bit float)");
    command.add_flag("--plot", render.plot, "draw the strength over time in the terminal");
    command.add_option("--width", render.plot_width, "plot width in columns (default 72)")
        ->check(number_between(10, 1000, NumberKind::whole));
    add_clefs_option(command, context.clef_search);
    command.add_option("--svg", render.svg,
                       "draw the signal and its envelope, with bar and note boundaries, "
                       "as an SVG picture");
    command.add_option("--png", render.png, "the same picture as a PNG image");
    add_actuator_option(command, state->actuator,
                        "--out FILE.csv then has t,written,uncompensated,compensated: the "
                        "strength written and what the actuator produces without and with "
                        "compensation; --plot, --svg and --png draw those three; without FILE "
                        "the score plays through the clefs vibscored uses (mapped or fitted, as "
                        "get clef NAME --device gives them), which the picture names");
    return [state, &context] {
        RenderRequest& request = state->request;
        if (const int failed = resolve_actuator(state->actuator, request.actuator, std::cerr)) {
            return failed;
        }
        if (state->actuator == kDaemonActuator) {
            request.device_clefs = daemon_clef_binder();
        }
        return render_document(request, context.clef_search, std::cout, std::cerr);
    };
}

VerbHandler declare_convert(CLI::App& command, VerbContext& context) {
    auto request = std::make_shared<ConvertRequest>();
    command.add_option("IN", request->in, "file to read")->required();
    command.add_option("OUT", request->out, "file to write")->required();
    command.add_option("--from", request->from,
                       "format of IN when its name does not tell: score, ahap, "
                       "android-json, android-xml, rtttl, midi");
    command.add_option("--to", request->to,
                       "format of OUT when its name does not tell: score, ahap, "
                       "android-json, android-xml, android-envelope, midi");
    command.add_option("--clef", request->clef,
                       "clef an import is written on: a clef file, or a clef's name found "
                       "as check finds one (--clefs, vibscored, the shipped clefs; "
                       "default lra-phone)");
    add_clefs_option(command, context.clef_search);
    command
        .add_option("--track", request->track,
                    "MIDI track to import, from 1 (default: the first with notes)")
        ->check(number_between(1, 65535, NumberKind::whole));
    command.add_flag("--loop", request->loop,
                     "Android: the pattern repeats (repeat index 0, <repeating>)");
    return [request, &context] {
        return convert(*request, context.clef_search, std::cout, std::cerr);
    };
}

VerbHandler declare_clef_fit(CLI::App& command, VerbContext& context) {
    struct State {
        ClefFitRequest request;
        std::string actuator = kDaemonActuator;
    };
    auto state = std::make_shared<State>();
    command.add_option("CLEF", state->request.clef, "VibClef file or registry clef name")
        ->required();
    command
        .add_option("--actuator", state->actuator,
                    "the actuator declared in FILE's [actuator] section (vibscored.conf will "
                    "do), or 'daemon' (the default): the one vibscored declares")
        ->type_name("FILE|daemon");
    command
        .add_option("-o,--output", state->request.output,
                    "write the fitted clef to OUT (default: standard output)")
        ->type_name("OUT");
    add_clefs_option(command, context.clef_search);
    return [state, &context] {
        // A fit needs an actuator: an empty name is not "none given" here (the default is the
        // daemon's), and reading on without one would use a declaration that is not there.
        if (state->actuator.empty()) {
            std::cerr << "vibscore: clef fit: --actuator needs a file or 'daemon', not an empty "
                         "name\n";
            return static_cast<int>(exit_usage);
        }
        std::optional<actuator::Declaration> declared;
        if (const int failed = resolve_actuator(state->actuator, declared, std::cerr)) {
            return failed;
        }
        state->request.actuator = *declared;
        return fit_clef_document(state->request, context.clef_search, std::cout, std::cerr);
    };
}

VerbHandler declare_info(CLI::App& command, VerbContext& context) {
    auto file = std::make_shared<std::string>();
    command
        .add_option("SCORE", *file,
                    "registry score name, or a VibScore or VibClef file (a name with a / or "
                    "ending in .xml, or a file that exists)")
        ->required();
    add_clefs_option(command, context.clef_search);
    return [file, &context] {
        // The same rule as play and show: a path, or else a registry name.
        if (editor::classify_source(*file).kind == editor::ScoreSource::Kind::registry) {
            return describe_registry_score(*file, std::cout, std::cerr);
        }
        return describe_document(*file, context.clef_search, std::cout, std::cerr);
    };
}

VerbHandler declare_show(CLI::App& command, VerbContext& context) {
    struct State {
        editor::ShowRequest request;
        std::string svg, png, actuator;
    };
    auto state = std::make_shared<State>();
    command
        .add_option("SCORE", state->request.score,
                    "registry name or VibScore file (with --svg/--png: or a clef, by file "
                    "or name)")
        ->required();
    command.add_option("--width", state->request.width, "columns (default: the terminal's)")
        ->check(number_between(20, 10000, NumberKind::whole));
    command.add_flag("--colour,--color", state->request.colour,
                     "ANSI colours even when not writing to a terminal");
    command.add_option("--svg", state->svg,
                       "draw the staff (or the clef) as an SVG picture instead");
    command.add_option("--png", state->png, "draw the staff (or the clef) as a PNG image instead");
    add_clefs_option(command, context.clef_search);
    add_actuator_option(command, state->actuator,
                        "with --svg/--png, a clef is drawn over the actuator's response (an LRA's "
                        "strength at full drive over frequency, and what each number reaches on "
                        "each string)");
    return [state, &context] {
        if (!state->svg.empty() || !state->png.empty()) {
            std::optional<actuator::Declaration> declared;
            if (const int failed = resolve_actuator(state->actuator, declared, std::cerr)) {
                return failed;
            }
            return show_picture(state->request.score, state->svg, state->png, context.clef_search,
                                std::cout, std::cerr, declared);
        }
        if (!state->actuator.empty()) {
            std::cerr
                << "vibscore: show --actuator draws a picture: give --svg FILE or --png FILE\n";
            return static_cast<int>(exit_usage);
        }
        return editor::show_score(state->request, std::cout, std::cerr);
    };
}

VerbHandler declare_edit(CLI::App& command, VerbContext&) {
    auto options = std::make_shared<editor::EditOptions>();
    command.add_option("SCORE", options->target,
                       "registry name or VibScore file (default: a new score)");
    command.add_option("--clef", options->clef,
                       "a new score's clef: registry clef or clef file (default lra-phone)");
    command.add_option("--buttons", options->buttons,
                       "evdev device whose keys are the six buttons (repeatable)");
    command.add_option("--keymap,--button-map", options->button_map,
                       "keys for the buttons, e.g. up=KEY_UP,select=KEY_ENTER,back=long:KEY_"
                       "POWER (default: phone volume and power keys)");
    command.add_flag("--grab", options->grab, "take the button devices' keys for the editor alone");
    return [options] { return editor::run_editor(*options, std::cerr); };
}

}  // namespace vibscore::client
