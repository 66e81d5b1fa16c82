#include "client/convert_verb.hpp"

#include <cctype>
#include <cerrno>
#include <cstdio>
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
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/limits.hpp"
#include "score/registry_names.hpp"
#include "score/score_xml.hpp"
#include "score/xml_support.hpp"

namespace vibscore::client {

namespace {

using formats::Format;

std::string seconds(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", value);
    return text;
}

// "0.428571 s, 140 bpm": the tempo as a reader takes it in (the file keeps every digit).
std::string tempo_text(double tempo) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g s, %.6g bpm", tempo, 60.0 / tempo);
    return text;
}

std::string counted(std::size_t count, const char* one, const char* many) {
    return std::to_string(count) + " " + (count == 1 ? one : many);
}

class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

enum class Side { in, out };

// The format a file is in, from --from/--to or its name; a .xml input is looked into. Messages
// offer only the formats that side takes.
Format format_of(const std::string& path, const std::string& named, Side side) {
    const char* option = side == Side::in ? "--from" : "--to";
    const auto names =
        side == Side::in ? formats::readable_format_names() : formats::writable_format_names();
    if (!named.empty()) {
        const auto format = formats::parse_format(named);
        if (!format) {
            throw UsageError("unknown format \"" + named + "\" for " + option + " (expected " +
                             names + ")");
        }
        return *format;
    }
    const auto format = formats::format_of_path(path);
    if (!format) {
        throw UsageError("cannot tell the format of \"" + path + "\" from its name; give " +
                         option + " (" + names + ")");
    }
    return *format;
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

// The clef an import lands on, and how the score will name it.
struct ImportClef {
    formats::ChosenClef chosen;
    // Named by a path: the file, which the score names by its path relative to the score
    // (rule 1 of docs/score-format.md). Named by a registry name: none; the score names it
    // NAME.clef.xml (rule 2), found as it was found here.
    std::optional<std::filesystem::path> file;
    std::string origin;  // where it was found, for the report
};

// `--clef`: a clef file (a path, or a file that exists), or a registry name looked up by the
// clef rule: --clefs folders, vibscored's registry, the shipped clefs.
ImportClef import_clef(const std::string& clef, const ClefSearch& search) {
    std::error_code ignored;
    const auto name = clef_name_in_href(clef);
    if (!name || std::filesystem::is_regular_file(clef, ignored)) {
        const std::filesystem::path path = clef;
        return {{clef_name(path), load_clef_file(path)}, path, path.string()};
    }
    const auto lookup = search.lookup();
    auto found = lookup.find(*name);
    if (!found) {
        throw std::runtime_error("no clef \"" + *name + "\" in " + lookup.places +
                                 "; --clef takes a clef file too");
    }
    return {{*name, std::move(found->clef)}, std::nullopt, found->origin};
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

// Refuses to write `path` over a file that holds another clef: the score's href would name it.
void check_no_other_clef(const std::filesystem::path& path, const Clef& clef,
                         const std::string& why) {
    std::error_code ignored;
    if (!std::filesystem::exists(path, ignored)) {
        return;
    }
    bool same = false;
    try {
        same = load_clef_file(path) == clef;
    } catch (const DocumentError&) {
    }
    if (!same) {
        throw std::runtime_error(path.string() + " exists with another clef, and " + why +
                                 "; move it away or convert into another directory");
    }
}

// Writes the score and any retimed clef beside it. The chosen clef keeps the name it was found
// by: its registry name, or its file's path relative to the score.
void write_imported(formats::ImportedScore imported, const std::filesystem::path& out,
                    const ImportClef& chosen, std::ostream& report) {
    const auto directory = out.has_parent_path() ? out.parent_path() : ".";
    for (std::size_t i = 0; i < imported.clefs.size(); ++i) {
        const auto& clef = imported.clefs[i];
        auto& declaration = imported.score.clefs[i];
        if (clef.retimed) {
            declaration.href = clef.id + std::string(kClefSuffix);
        } else if (chosen.file) {
            declaration.href =
                std::filesystem::absolute(*chosen.file)
                    .lexically_normal()
                    .lexically_relative(std::filesystem::absolute(directory).lexically_normal())
                    .string();
        } else {
            declaration.href = clef.id + std::string(kClefSuffix);
            // A file of that name beside the score would be the clef (rule 1), not the
            // registry's.
            check_no_other_clef(directory / declaration.href, clef.clef,
                                "the score names clef " + clef.id + " by that name");
        }
    }
    // The whole score must be a document the reader takes before anything is written.
    const auto text = write_score(imported.score);
    if (text.size() > limits::document_bytes) {
        throw DocumentError({out.string()}, "the score would be " + std::to_string(text.size()) +
                                                " bytes, larger than the " +
                                                std::to_string(limits::document_bytes) +
                                                "-byte limit for a document; nothing written");
    }
    // Every copy is checked before any is written: a refusal leaves nothing behind.
    std::vector<std::size_t> copies;
    for (std::size_t i = 0; i < imported.clefs.size(); ++i) {
        if (imported.clefs[i].retimed) {
            check_no_other_clef(directory / imported.score.clefs[i].href, imported.clefs[i].clef,
                                "the score names its copy at that tempo so");
            copies.push_back(i);
        }
    }
    for (const auto i : copies) {
        const auto& clef = imported.clefs[i];
        const auto clef_file = directory / imported.score.clefs[i].href;
        std::error_code ignored;
        if (!std::filesystem::exists(clef_file, ignored)) {
            write_file(clef_file, write_clef(clef.clef));
            report << "wrote " << clef_file.string() << " (clef " << clef.id << ": tempo "
                   << tempo_text(clef.clef.tempo) << ")\n";
        }
    }
    write_file(out, text);
}

}  // namespace

int convert(const ConvertRequest& request, const ClefSearch& clefs, std::ostream& out,
            std::ostream& err) {
    try {
        Format from = format_of(request.in, request.from, Side::in);
        if (request.from.empty() && from == Format::score) {
            from = formats::format_of_xml_text(read_document_file(request.in));
        }
        const Format to = format_of(request.out, request.to, Side::out);
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
            const auto bundle = load_score(request.in, clefs).bundle;
            write_file(request.out, export_track(to, bundle, request));
            out << "wrote " << request.out << " (" << formats::to_string(to) << ")\n";
            return exit_ok;
        }
        const auto chosen = import_clef(request.clef, clefs);
        auto imported = import_file(from, request.in, chosen.chosen, request);
        for (const auto& warning : imported.warnings) {
            err << format(Diagnostic{warning.where, "warning: " + warning.message}) << "\n";
        }
        if (to != Format::score) {
            const auto bundle = bundle_of(imported, request.in);
            write_file(request.out, export_track(to, bundle, request));
            out << "wrote " << request.out << " (" << formats::to_string(to) << ")\n";
            return exit_ok;
        }
        write_imported(std::move(imported), request.out, chosen, out);
        // What was written must check and render, as any score, found by the same rule.
        const auto bundle = load_score(request.out, clefs).bundle;
        const render::Performance performance(bundle);
        std::size_t notes = 0;
        for (const auto& timing : performance.timeline()) {
            notes += timing.is_note ? 1 : 0;
        }
        out << "wrote " << request.out << " (" << counted(bundle.score.bars.size(), "bar", "bars")
            << ", " << counted(notes, "note", "notes") << ", " << seconds(performance.duration())
            << " s) on clef " << chosen.chosen.name << " from "
            << (chosen.origin == kRegistryOrigin ? "vibscored's registry" : chosen.origin) << "\n";
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
