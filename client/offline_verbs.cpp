#include "client/offline_verbs.hpp"

#include <cstdio>
#include <map>

#include "client/signal_output.hpp"
#include "client/terminal_plot.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"

namespace vibscore::client {

namespace {

std::string fixed(double value, int decimals = 3) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

std::string number(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string count(std::size_t n, const char* noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string clef_summary(const Clef& clef) {
    return std::string(to_string(clef.type)) + ", tempo " + number(clef.tempo) + " s, " +
           count(clef.strings.size(), "string") + ", " + count(clef.numbers.size(), "number");
}

void report(const DocumentError& error, std::ostream& err) {
    for (const auto& diagnostic : error.diagnostics()) {
        err << format(diagnostic) << "\n";
    }
}

void describe_clef(const std::string& file, const Clef& clef, std::ostream& out) {
    out << "clef:     " << file << "\n"
        << "type:     " << to_string(clef.type) << "\n"
        << "tempo:    " << number(clef.tempo) << " s per quarter note\n"
        << "numbers: ";
    for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
        out << " " << n + 1 << "=" << number(clef.numbers[n]);
    }
    out << "\nstrings:\n";
    for (std::size_t s = clef.strings.size(); s-- > 0;) {
        out << "  " << s + 1 << "  ";
        if (clef.type == ClefType::sine) {
            out << number(clef.strings[s].frequency) << " Hz\n";
        } else {
            out << clef.strings[s].points.size() << " points\n";
        }
    }
}

}  // namespace

void describe_score(const ScoreBundle& bundle, std::ostream& out) {
    const render::Performance performance(bundle);
    std::size_t notes = 0;
    for (const auto& timing : performance.timeline()) {
        notes += timing.is_note ? 1 : 0;
    }
    out << "title:    " << (bundle.score.title.empty() ? "(untitled)" : bundle.score.title) << "\n"
        << "file:     " << bundle.file << "\n"
        << "duration: " << fixed(performance.duration()) << " s ("
        << count(bundle.score.bars.size(), "bar") << ", " << count(notes, "note") << ", "
        << count(performance.timeline().size() - notes, "rest") << ")\n"
        << "clefs:\n";
    std::map<std::string, bool> used;
    for (const auto& bar : bundle.score.bars) {
        used[bar.clef] = true;
    }
    for (const auto& declaration : bundle.score.clefs) {
        out << "  " << declaration.id << "  " << declaration.href << "  "
            << clef_summary(bundle.clefs.at(declaration.id))
            << (used.contains(declaration.id) ? "" : "  (declared, not used)") << "\n";
    }
    out << "bars:\n";
    double start = 0.0;
    for (std::size_t b = 0; b < bundle.score.bars.size(); ++b) {
        const auto& bar = bundle.score.bars[b];
        const double beats = Score::beat_count(bar);
        const double seconds = beats * bundle.clef_of(bar).tempo;
        out << "  " << b + 1 << "  clef " << bar.clef << "  " << number(beats) << " beats"
            << (beats < 4   ? " (short)"
                : beats > 4 ? " (long)"
                            : "")
            << "  at " << fixed(start) << " s, " << fixed(seconds) << " s\n";
        start += seconds;
    }
}

int check_documents(const std::vector<std::string>& files, std::ostream& out, std::ostream& err) {
    int failed = 0;
    for (const auto& file : files) {
        try {
            const auto text = read_document_file(file);
            if (document_kind(text, file) == DocumentKind::clef) {
                const Clef clef = read_clef(text, file);
                out << file << ": ok (clef: " << clef_summary(clef) << ")\n";
            } else {
                const auto bundle = load_score_file(file);
                const render::Performance performance(bundle);
                out << file << ": ok (score: " << count(bundle.score.bars.size(), "bar") << ", "
                    << fixed(performance.duration()) << " s)\n";
            }
        } catch (const DocumentError& error) {
            report(error, err);
            ++failed;
        }
    }
    if (failed > 0 && files.size() > 1) {
        err << failed << " of " << files.size() << " documents are invalid\n";
    }
    return failed == 0 ? exit_ok : exit_failed;
}

int render_document(const RenderRequest& request, std::ostream& out, std::ostream& err) {
    if (request.out.empty() && !request.plot) {
        err << "render: nothing to do: give --out FILE.csv|FILE.wav and/or --plot\n";
        return exit_usage;
    }
    if (!request.out.empty()) {
        try {
            signal_format_for(request.out);
        } catch (const std::invalid_argument& error) {
            err << "render: " << error.what() << "\n";
            return exit_usage;
        }
    }
    try {
        const auto text = read_document_file(request.file);
        if (document_kind(text, request.file) == DocumentKind::clef) {
            err << request.file << ": is a clef; render takes a score (VibScore)\n";
            return exit_usage;
        }
        const auto bundle = load_score_file(request.file);
        const render::Performance performance(bundle);
        if (request.plot) {
            out << (bundle.score.title.empty() ? request.file : bundle.score.title) << "  ("
                << fixed(performance.duration()) << " s, peak "
                << number(performance.peak_amplitude()) << ")\n";
            plot_envelope(out, performance, request.plot_width, 8);
        }
        if (!request.out.empty()) {
            const auto samples = write_signal(performance, request.rate, request.out);
            out << "wrote " << request.out << ": " << samples << " samples at " << request.rate
                << " Hz, " << fixed(performance.duration()) << " s\n";
        }
        return exit_ok;
    } catch (const DocumentError& error) {
        report(error, err);
    } catch (const std::exception& error) {
        err << "render: " << error.what() << "\n";
    }
    return exit_failed;
}

int describe_document(const std::string& file, std::ostream& out, std::ostream& err) {
    try {
        const auto text = read_document_file(file);
        if (document_kind(text, file) == DocumentKind::clef) {
            describe_clef(file, read_clef(text, file), out);
        } else {
            describe_score(load_score_file(file), out);
        }
        return exit_ok;
    } catch (const DocumentError& error) {
        report(error, err);
        return exit_failed;
    }
}

}  // namespace vibscore::client
