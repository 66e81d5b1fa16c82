// vibscore: the command-line client. Offline verbs work on files without the daemon.
#include <CLI/CLI.hpp>

#include <iostream>

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
        "info", "Show a score's title, duration, bars and clefs, or a clef's mapping.");
    info->add_option("FILE", info_file, "VibScore or VibClef document")->required();

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
    return describe_document(info_file, std::cout, std::cerr);
}
