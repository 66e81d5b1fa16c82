#include "client/convert_verb.hpp"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "client/formats/ahap.hpp"
#include "client/formats/android.hpp"
#include "client/formats/formats.hpp"
#include "client/formats/midi.hpp"
#include "client/formats/rtttl.hpp"
#include "client/formats/sound_events.hpp"
#include "client/offline_verbs.hpp"
#include "config.h"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"
#include "score/xml_support.hpp"

namespace vibscore::client {

namespace {

using formats::Format;

constexpr std::string_view kClefSuffix = ".clef.xml";

std::string seconds(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", value);
    return text;
}

class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The format a file is in, from --from/--to or its name; a .xml input is looked into.
Format format_of(const std::string& path, const std::string& named, const char* option) {
    if (!named.empty()) {
        const auto format = formats::parse_format(named);
        if (!format) {
            throw UsageError("unknown format \"" + named + "\" for " + option + " (expected " +
                             std::string(formats::format_names()) + ")");
        }
        return *format;
    }
    const auto format = formats::format_of_path(path);
    if (!format) {
        throw UsageError("cannot tell the format of \"" + path + "\" from its name; give " +
                         option + " (" + std::string(formats::format_names()) + ")");
    }
    return *format;
}

// A clef file, or a shipped clef's name looked up in $VIBSCORE_CLEFDIR or the installed clefs.
std::filesystem::path clef_path(const std::string& clef) {
    std::error_code ignored;
    if (clef.find('/') != std::string::npos || clef.ends_with(".xml") ||
        std::filesystem::is_regular_file(clef, ignored)) {
        return clef;
    }
    const char* directory = std::getenv("VIBSCORE_CLEFDIR");
    return std::filesystem::path(directory != nullptr ? directory : VIBSCORE_CLEFDIR) /
           (clef + std::string(kClefSuffix));
}

std::string clef_name(const std::filesystem::path& path) {
    std::string name = path.filename().string();
    for (const std::string_view suffix : {kClefSuffix, std::string_view(".xml")}) {
        if (name.ends_with(suffix)) {
            name.resize(name.size() - suffix.size());
            break;
        }
    }
    // Keep the name a valid clef id.
    for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') {
            c = '-';
        }
    }
    return name.empty() ? "clef" : name.substr(0, 48);
}

// Writes beside the target and renames over it, so the file appears whole or not at all.
void write_file(const std::filesystem::path& path, const std::string& content) {
    auto temporary = path;
    temporary += ".partial";
    {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        file << content;
        file.flush();
        if (!file) {
            const std::string reason = std::strerror(errno);
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw std::runtime_error(path.string() + ": cannot write: " + reason);
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw std::runtime_error(path.string() + ": " + error.message());
    }
}

std::string export_track(Format format, const ScoreBundle& bundle, const ConvertRequest& request) {
    const formats::AndroidOptions android{request.loop};
    switch (format) {
        case Format::ahap:
            return formats::write_ahap(formats::sound_track(bundle));
        case Format::android_json:
            return formats::write_android_json(formats::sound_track(bundle), android);
        case Format::android_xml:
            return formats::write_android_xml(formats::sound_track(bundle), android);
        case Format::android_envelope:
            return formats::write_android_envelope(formats::sound_track(bundle), android);
        case Format::midi:
            return formats::write_midi(bundle);
        case Format::score:
        case Format::rtttl:
            break;
    }
    throw UsageError("cannot write " + std::string(formats::to_string(format)));
}

formats::ImportedScore import_file(Format format, const std::string& path,
                                   const formats::ChosenClef& chosen,
                                   const ConvertRequest& request) {
    const auto bytes = read_document_file(path);
    switch (format) {
        case Format::ahap:
            return formats::read_ahap(bytes, path, chosen);
        case Format::android_json:
            return formats::read_android_json(bytes, path, chosen);
        case Format::android_xml:
            return formats::read_android_xml(bytes, path, chosen);
        case Format::rtttl:
            return formats::read_rtttl(bytes, path, chosen);
        case Format::midi:
            return formats::read_midi(
                bytes, path, chosen,
                request.track > 0 ? std::optional<int>(request.track) : std::nullopt);
        case Format::score:
        case Format::android_envelope:
            break;
    }
    throw UsageError("cannot read " + std::string(formats::to_string(format)));
}

// The imported score bound to its clefs in memory, as if read from files.
ScoreBundle bundle_of(const formats::ImportedScore& imported, const std::string& file) {
    ParsedScore parsed{imported.score, {}};
    parsed.where.clefs.resize(imported.score.clefs.size());
    parsed.where.bars.resize(imported.score.bars.size());
    for (const auto& bar : imported.score.bars) {
        parsed.where.symbols.emplace_back(bar.symbols.size());
    }
    return bind_clefs(std::move(parsed), file,
                      [&](const ClefDeclaration& declaration, const SourceLocation&) {
                          for (const auto& clef : imported.clefs) {
                              if (clef.id == declaration.id) {
                                  return clef.clef;
                              }
                          }
                          throw DocumentError({file}, "no clef " + declaration.id);
                      });
}

// Writes the score and any retimed clef beside it; hrefs of the chosen clef point back to it.
void write_imported(formats::ImportedScore imported, const std::filesystem::path& out,
                    const std::filesystem::path& chosen_path, std::ostream& report) {
    const auto directory = out.has_parent_path() ? out.parent_path() : ".";
    for (std::size_t i = 0; i < imported.clefs.size(); ++i) {
        const auto& clef = imported.clefs[i];
        auto& declaration = imported.score.clefs[i];
        if (!clef.retimed) {
            // Beside or below the score a relative href keeps the pair movable; elsewhere an
            // absolute one is clearer than a climb of ../.
            const auto relative = std::filesystem::proximate(chosen_path, directory);
            declaration.href =
                relative.empty() || *relative.begin() == ".."
                    ? std::filesystem::absolute(chosen_path).lexically_normal().string()
                    : relative.string();
            continue;
        }
        declaration.href = clef.id + std::string(kClefSuffix);
        const auto clef_file = directory / declaration.href;
        const auto text = write_clef(clef.clef);
        std::error_code ignored;
        if (std::filesystem::exists(clef_file, ignored)) {
            const auto existing = read_document_file(clef_file);
            if (existing != text) {
                throw std::runtime_error(clef_file.string() +
                                         " exists with other content; move it away or convert "
                                         "into another directory");
            }
        } else {
            write_file(clef_file, text);
            report << "wrote " << clef_file.string() << " (clef " << declaration.id << ": tempo "
                   << xml::format_number(clef.clef.tempo) << " s)\n";
        }
    }
    write_file(out, write_score(imported.score));
}

}  // namespace

int convert(const ConvertRequest& request, std::ostream& out, std::ostream& err) {
    try {
        Format from = format_of(request.in, request.from, "--from");
        if (request.from.empty() && from == Format::score) {
            from = formats::format_of_xml_text(read_document_file(request.in));
        }
        const Format to = format_of(request.out, request.to, "--to");
        if (!formats::can_read(from)) {
            throw UsageError(std::string(formats::to_string(from)) +
                             " is not read on its own; android-xml reads envelopes too");
        }
        if (!formats::can_write(to)) {
            throw UsageError("vibscore reads " + std::string(formats::to_string(to)) +
                             " but does not write it");
        }
        if (from == to) {
            throw UsageError("both files are " + std::string(formats::to_string(to)) +
                             ": nothing to convert");
        }
        if (from == Format::score) {
            const auto bundle = load_score_file(request.in);
            write_file(request.out, export_track(to, bundle, request));
            out << "wrote " << request.out << " (" << formats::to_string(to) << ")\n";
            return exit_ok;
        }
        const auto chosen_path = clef_path(request.clef);
        const formats::ChosenClef chosen{clef_name(chosen_path), load_clef_file(chosen_path)};
        auto imported = import_file(from, request.in, chosen, request);
        if (to != Format::score) {
            const auto bundle = bundle_of(imported, request.in);
            write_file(request.out, export_track(to, bundle, request));
            out << "wrote " << request.out << " (" << formats::to_string(to) << ")\n";
            return exit_ok;
        }
        write_imported(std::move(imported), request.out, chosen_path, out);
        // What was written must check and render, as any score.
        const auto bundle = load_score_file(request.out);
        const render::Performance performance(bundle);
        std::size_t notes = 0;
        for (const auto& timing : performance.timeline()) {
            notes += timing.is_note ? 1 : 0;
        }
        out << "wrote " << request.out << " (" << bundle.score.bars.size() << " bars, " << notes
            << " notes, " << seconds(performance.duration()) << " s)\n";
        return exit_ok;
    } catch (const UsageError& error) {
        err << "convert: " << error.what() << "\n";
        return exit_usage;
    } catch (const DocumentError& error) {
        for (const auto& diagnostic : error.diagnostics()) {
            err << format(diagnostic) << "\n";
        }
    } catch (const std::exception& error) {
        err << "convert: " << error.what() << "\n";
    }
    return exit_failed;
}

}  // namespace vibscore::client
