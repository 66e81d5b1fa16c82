#include "client/offline_verbs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string_view>

#include "client/pictures/response_picture.hpp"
#include "client/pictures/signal_picture.hpp"
#include "client/signal_output.hpp"
#include "client/terminal_plot.hpp"
#include "common/number_text.hpp"
#include "daemon/render/actuator_response.hpp"
#include "daemon/render/fitting/actuator_check.hpp"
#include "daemon/render/fitting/clef_check.hpp"
#include "daemon/render/performance.hpp"
#include "daemon/render/sampler.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/registry_names.hpp"

namespace vibscore::client {

namespace {

std::string fixed(double value, int decimals = 3) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

std::string number(double value) {
    return number_text(value);
}

std::string padded(const std::string& text, std::size_t width) {
    return text + std::string(width - std::min(width, text.size()), ' ');
}

std::string count(std::size_t n, const char* noun) {
    return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// Seconds per quarter note at six digits (a tempo copy made for 140 bpm holds 3/7 s).
std::string tempo_text(double seconds) {
    return rounded_text(seconds) + " s";
}

std::string clef_summary(const Clef& clef) {
    return std::string(to_string(clef.type)) + ", tempo " + tempo_text(clef.tempo) + ", " +
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
        << "tempo:    " << tempo_text(clef.tempo) << " per quarter note ("
        << rounded_text(60.0 / clef.tempo, 4) << " bpm)\n"
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

void describe_score(const LoadedScore& loaded, std::ostream& out) {
    const ScoreBundle& bundle = loaded.bundle;
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
    // One row per clef, its columns lined up: id, href, what the clef is, where it was found.
    std::size_t id_width = 0, href_width = 0, summary_width = 0;
    for (const auto& declaration : bundle.score.clefs) {
        id_width = std::max(id_width, declaration.id.size());
        href_width = std::max(href_width, declaration.href.size());
        summary_width =
            std::max(summary_width, clef_summary(bundle.clefs.at(declaration.id)).size());
    }
    for (const auto& declaration : bundle.score.clefs) {
        const auto origin = loaded.clef_origins.find(declaration.id);
        out << "  " << padded(declaration.id, id_width) << "  "
            << padded(declaration.href, href_width) << "  "
            << padded(clef_summary(bundle.clefs.at(declaration.id)), summary_width) << "  from "
            << (origin == loaded.clef_origins.end() ? "?" : origin->second)
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
            << "  at " << fixed(start) << " s, " << fixed(seconds) << " s long\n";
        start += seconds;
    }
}

namespace {

// Samples a second of what a declared actuator produces, for --plot and the picture: a pixel or
// a column is at least a millisecond for all but the shortest scores.
constexpr double kResponsePictureRate = 1000.0;

constexpr std::string_view kActuatorCsvHeader = "t,written,uncompensated,compensated\n";

// `render --actuator --out F.csv` holds the response in memory, a row a sample: refused before
// it is computed when even rows of one-character numbers ("0,0,0,0") would pass the limit every
// signal file has (client/signal_output.hpp).
void check_actuator_csv_rows(std::uint64_t rows, std::uint32_t rate, const std::string& path) {
    const std::uint64_t least = kActuatorCsvHeader.size() + rows * 8;
    if (least > kMaxSignalFileBytes) {
        throw SignalTooLarge(path + " would take at least " + std::to_string(least) +
                             " bytes, more than the " + std::to_string(kMaxSignalFileBytes) +
                             " bytes (4 GiB) a signal file may take; use a lower --rate than " +
                             std::to_string(rate) + " Hz");
    }
}

// The strengths written and produced, one row per sample: what `render --actuator --out F.csv`
// writes, for plots and spreadsheets. Refused before the file is created when a strength is not
// finite (the declared model overflowed: a NaN in a spreadsheet helps no one) or when the rows
// would pass the limit of a signal file.
std::size_t write_actuator_csv(const render::ActuatorResponse& response, const std::string& path) {
    std::uint64_t bytes = kActuatorCsvHeader.size();
    for (std::size_t k = 0; k < response.written.size(); ++k) {
        const double t = static_cast<double>(k) / response.rate_hz;
        for (const double value :
             {response.written[k], response.uncompensated[k], response.compensated[k]}) {
            if (!std::isfinite(value)) {
                throw std::runtime_error(
                    "the actuator's model gives a strength of " + number(value) +
                    " at t = " + number(t) + " s, so " + path +
                    " is not written; the [actuator] declaration cannot be simulated");
            }
            bytes += number(value).size() + 1;
        }
        bytes += number(t).size() + 1;
    }
    if (bytes > kMaxSignalFileBytes) {
        throw SignalTooLarge(path + " would take " + std::to_string(bytes) +
                             " bytes, more than the " + std::to_string(kMaxSignalFileBytes) +
                             " bytes (4 GiB) a signal file may take; use a lower --rate");
    }
    std::ofstream csv(path);
    csv << kActuatorCsvHeader;
    for (std::size_t k = 0; k < response.written.size(); ++k) {
        csv << number(static_cast<double>(k) / response.rate_hz) << ","
            << number(response.written[k]) << "," << number(response.uncompensated[k]) << ","
            << number(response.compensated[k]) << "\n";
    }
    csv.close();
    if (!csv) {
        throw std::runtime_error(path + ": cannot write");
    }
    return response.written.size();
}

}  // namespace

namespace {

// How a bar's clef is named in pictures and lines: its registry name, or its file's name.
std::string written_clef_name(const ClefDeclaration& declaration) {
    if (const auto name = clef_name_in_href(declaration.href)) {
        return *name;
    }
    return std::filesystem::path(declaration.href).filename().string();
}

// The score as it is to be drawn or checked: through the device clefs when asked, with the
// words that say which clefs those are.
struct ClefsUsed {
    ScoreBundle bundle;
    std::map<std::string, std::string> names;  // by clef id
    std::string said;
};

ClefsUsed clefs_used(const LoadedScore& loaded, const DeviceClefBinder& device_clefs) {
    if (device_clefs) {
        auto bound = device_clefs(loaded);
        return {std::move(bound.bundle), std::move(bound.names),
                "clefs as vibscored plays them: " + bound.said};
    }
    ClefsUsed used{loaded.bundle, {}, "clefs as written: "};
    bool first = true;
    for (const auto& declaration : loaded.bundle.score.clefs) {
        used.names[declaration.id] = written_clef_name(declaration);
        used.said += (first ? "" : ", ") + used.names[declaration.id];
        first = false;
    }
    return used;
}

// The clef each bar plays through, by name, in bar order.
std::vector<std::string> bar_clef_names(const ClefsUsed& used) {
    std::vector<std::string> names;
    for (const auto& bar : used.bundle.score.bars) {
        const auto found = used.names.find(bar.clef);
        names.push_back(found == used.names.end() ? bar.clef : found->second);
    }
    return names;
}

}  // namespace

int check_documents(const std::vector<std::string>& files, const ClefSearch& clefs,
                    std::ostream& out, std::ostream& err,
                    const std::optional<actuator::Declaration>& declared,
                    const DeviceClefBinder& device_clefs) {
    int failed = 0;
    std::size_t warned = 0;
    std::size_t checked = 0;
    const auto check_clef = [&](const std::string& label, const Clef& clef) {
        out << label << ": ok (clef: " << clef_summary(clef) << ")\n";
        ++checked;
        if (declared) {
            for (const auto& warning : render::clef_warnings(clef, *declared)) {
                err << label << ": warning: " << warning << "\n";
                ++warned;
            }
        }
    };
    const auto check_score = [&](const std::string& label, const LoadedScore& loaded) {
        const auto used = clefs_used(loaded, declared ? device_clefs : DeviceClefBinder{});
        const render::Performance performance(used.bundle);
        out << label << ": ok (score: " << count(used.bundle.score.bars.size(), "bar") << ", "
            << fixed(performance.duration()) << " s)\n";
        ++checked;
        if (declared) {
            if (device_clefs) {
                out << label << ": " << used.said << "\n";
            }
            for (const auto& warning :
                 render::actuator_warnings(used.bundle, performance, *declared)) {
                err << label << ": warning: " << render::describe(warning) << "\n";
                ++warned;
            }
        }
    };
    for (const auto& file : files) {
        try {
            if (!names_a_file(file)) {
                const auto named = load_registry_document(file, clefs);
                named.clef ? check_clef(file, *named.clef) : check_score(file, *named.score);
                continue;
            }
            const auto text = read_document_file(file);
            if (document_kind(text, file) == DocumentKind::clef) {
                check_clef(file, read_clef(text, file));
            } else {
                check_score(file, load_score(file, clefs));
            }
        } catch (const DocumentError& error) {
            report(error, err);
            ++failed;
        } catch (const std::runtime_error& error) {
            err << "vibscore: " << error.what() << "\n";
            ++failed;
        }
    }
    if (failed > 0 && files.size() > 1) {
        err << failed << " of " << files.size() << " documents are invalid\n";
    }
    // Only when something was checked against it: "0 warnings" about nothing is not true.
    if (declared && checked > 0) {
        out << count(warned, "warning") << " for the actuator (" << actuator::describe(*declared)
            << ")\n";
    }
    return failed == 0 ? exit_ok : exit_failed;
}

int render_document(const RenderRequest& request, const ClefSearch& clefs, std::ostream& out,
                    std::ostream& err) {
    if (request.out.empty() && !request.plot && request.svg.empty() && request.png.empty()) {
        err << "render: nothing to do: give --out FILE.csv|FILE.wav, --plot, --svg FILE or "
               "--png FILE\n";
        return exit_usage;
    }
    const std::optional<actuator::Declaration>& declared = request.actuator;
    if (declared && !request.out.empty() && !request.out.ends_with(".csv")) {
        err << "render: --actuator writes strengths to a .csv file, not " << request.out << "\n";
        return exit_usage;
    }
    try {
        if (!request.out.empty()) {
            signal_format_for(request.out);
        }
        for (const auto& picture : {request.svg, request.png}) {
            if (!picture.empty()) {
                pictures::picture_format_for(picture);
            }
        }
    } catch (const std::invalid_argument& error) {
        err << "render: " << error.what() << "\n";
        return exit_usage;
    }
    try {
        std::optional<LoadedScore> loaded;
        if (names_a_file(request.file)) {
            const auto text = read_document_file(request.file);
            if (document_kind(text, request.file) == DocumentKind::clef) {
                err << request.file << ": is a clef; render takes a score (VibScore)\n";
                return exit_usage;
            }
            loaded = load_score(request.file, clefs);
        } else {
            auto named = load_registry_document(request.file, clefs);
            if (named.clef) {
                err << request.file << ": is a clef; render takes a score (VibScore)\n";
                return exit_usage;
            }
            loaded = std::move(named.score);
        }
        const auto used = clefs_used(*loaded, declared ? request.device_clefs : DeviceClefBinder{});
        const ScoreBundle& bundle = used.bundle;
        const render::Performance performance(bundle);
        const std::string title = bundle.score.title.empty() ? request.file : bundle.score.title;
        // What the declared actuator makes of the score, sampled at `rate`.
        const auto response = [&](double rate) {
            render::ResponseOptions options;
            options.rate_hz = rate;
            options.reverse = declared->brake == actuator::Brake::reverse;
            return render::actuator_response(performance, *declared, options);
        };
        if (request.plot) {
            out << title << "  (" << fixed(performance.duration()) << " s, peak "
                << number(performance.peak_amplitude()) << ")\n";
            if (declared) {
                out << "on the actuator: " << actuator::describe(*declared) << "\n"
                    << used.said << "\n";
                plot_response(out, response(kResponsePictureRate), request.plot_width, 4);
            } else {
                plot_envelope(out, performance, request.plot_width, 8);
            }
        }
        if (!request.out.empty() && declared) {
            check_actuator_csv_rows(render::sample_index_at(performance.duration(), request.rate),
                                    request.rate, request.out);
            const auto samples = write_actuator_csv(response(request.rate), request.out);
            out << "wrote " << request.out << ": " << samples << " samples at " << request.rate
                << " Hz of the written strength and what the actuator produces without and with "
                   "compensation\n";
        } else if (!request.out.empty()) {
            const auto samples = write_signal(performance, request.rate, request.out);
            out << "wrote " << request.out << ": " << samples << " samples at " << request.rate
                << " Hz, " << fixed(performance.duration()) << " s\n";
        }
        if (!request.svg.empty() || !request.png.empty()) {
            std::unique_ptr<pictures::Drawing> picture;
            if (declared) {
                pictures::ResponsePicture::Options options;
                options.bar_clefs = bar_clef_names(used);
                picture = std::make_unique<pictures::ResponsePicture>(
                    performance, response(kResponsePictureRate), title,
                    "on the actuator: " + actuator::describe(*declared) + "\n" + used.said,
                    options);
            } else {
                picture = std::make_unique<pictures::SignalPicture>(performance, title);
            }
            for (const auto& path : {request.svg, request.png}) {
                if (!path.empty()) {
                    pictures::write_picture(*picture, path);
                    out << "wrote " << path << "\n";
                }
            }
        }
        return exit_ok;
    } catch (const DocumentError& error) {
        report(error, err);
    } catch (const std::exception& error) {
        err << "render: " << error.what() << "\n";
    }
    return exit_failed;
}

int describe_document(const std::string& file, const ClefSearch& clefs, std::ostream& out,
                      std::ostream& err) {
    try {
        const auto text = read_document_file(file);
        if (document_kind(text, file) == DocumentKind::clef) {
            describe_clef(file, read_clef(text, file), out);
        } else {
            describe_score(load_score(file, clefs), out);
        }
        return exit_ok;
    } catch (const DocumentError& error) {
        report(error, err);
        return exit_failed;
    }
}

}  // namespace vibscore::client
