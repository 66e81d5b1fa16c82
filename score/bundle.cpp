#include "score/bundle.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "score/clef_xml.hpp"
#include "score/document_error.hpp"
#include "score/limits.hpp"
#include "score/registry_names.hpp"
#include "score/xml_support.hpp"

namespace vibscore {

namespace {

void check_notes_against_clefs(const ScoreBundle& bundle, DiagnosticSink& sink) {
    double seconds = 0.0;
    for (size_t b = 0; b < bundle.score.bars.size(); ++b) {
        const auto& bar = bundle.score.bars[b];
        const auto found = bundle.clefs.find(bar.clef);
        if (found == bundle.clefs.end()) {
            continue;  // already reported: the clef could not be resolved
        }
        const Clef& clef = found->second;
        seconds += Score::beat_count(bar) * clef.tempo;
        for (size_t s = 0; s < bar.symbols.size(); ++s) {
            const auto* note = std::get_if<Note>(&bar.symbols[s]);
            if (note == nullptr) {
                continue;
            }
            const auto& where = bundle.where.symbols[b][s];
            if (static_cast<size_t>(note->string) > clef.strings.size()) {
                sink.report(where, "string " + std::to_string(note->string) + " is beyond clef \"" +
                                       bar.clef + "\", which defines strings 1 to " +
                                       std::to_string(clef.strings.size()));
            }
            if (static_cast<size_t>(note->number) > clef.numbers.size()) {
                sink.report(where, "number " + std::to_string(note->number) + " is beyond clef \"" +
                                       bar.clef + "\", which defines numbers 1 to " +
                                       std::to_string(clef.numbers.size()));
            }
        }
    }
    // A microsecond of slack: a sum over thousands of bars at a tempo like 0.2 s, which no
    // binary fraction is, builds up rounding, and a score of exactly an hour must pass.
    if (seconds > limits::max_score_seconds + 1e-6) {
        sink.report(bundle.where.document,
                    "the score lasts " + xml::format_number(seconds) + " s; the limit is " +
                        xml::format_number(limits::max_score_seconds) + " s");
    }
}

}  // namespace

ScoreBundle bind_clefs(ParsedScore parsed, std::string file, const ClefResolver& resolve) {
    ScoreBundle bundle{std::move(file), std::move(parsed.score), std::move(parsed.where), {}};
    DiagnosticSink sink;
    for (size_t i = 0; i < bundle.score.clefs.size(); ++i) {
        const auto& declaration = bundle.score.clefs[i];
        try {
            bundle.clefs.emplace(declaration.id, resolve(declaration, bundle.where.clefs[i]));
        } catch (const DocumentError& error) {
            for (const auto& diagnostic : error.diagnostics()) {
                sink.report(diagnostic.where, diagnostic.message);
            }
        }
    }
    check_notes_against_clefs(bundle, sink);
    sink.throw_if_any();
    return bundle;
}

std::string read_document_file(const std::filesystem::path& path) {
    const SourceLocation where{path.string()};
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        throw DocumentError(where, "is a directory, not a document");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw DocumentError(where, std::string("cannot open: ") + std::strerror(errno));
    }
    std::string text;
    char buffer[65536];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        text.append(buffer, static_cast<size_t>(in.gcount()));
        if (text.size() > limits::document_bytes) {
            throw DocumentError(where, "larger than the " + std::to_string(limits::document_bytes) +
                                           "-byte limit for a document");
        }
    }
    if (in.bad()) {
        throw DocumentError(where, std::string("read failed: ") + std::strerror(errno));
    }
    return text;
}

std::string_view to_string(DocumentKind kind) {
    return kind == DocumentKind::score ? "score" : "clef";
}

std::optional<DocumentKind> parse_document_kind(std::string_view text) {
    if (text == "score" || text == "scores") {
        return DocumentKind::score;
    }
    if (text == "clef" || text == "clefs") {
        return DocumentKind::clef;
    }
    return std::nullopt;
}

DocumentKind document_kind(std::string_view text, const std::string& file) {
    const auto root = xml::root_name(text);
    if (root == "VibScore") {
        return DocumentKind::score;
    }
    if (root == "VibClef") {
        return DocumentKind::clef;
    }
    // Let the parser name the line and column of malformed XML.
    const xml::Source source(text, file);
    throw DocumentError(source.where(source.root()),
                        "root element is <" + root + ">, expected <VibScore> or <VibClef>");
}

Clef load_clef_file(const std::filesystem::path& path) {
    return read_clef(read_document_file(path), path.string());
}

ScoreBundle load_score_file(const std::filesystem::path& path, const NamedClefLookup& named,
                            std::map<std::string, std::string>* origins) {
    const auto file = path.string();
    auto parsed = read_score(read_document_file(path), file);
    const auto directory = path.parent_path();
    return bind_clefs(
        std::move(parsed), file,
        [&](const ClefDeclaration& declaration, const SourceLocation& declared_at) {
            const auto clef_path = directory / declaration.href;
            const auto name = clef_name_in_href(declaration.href);
            std::error_code ignored;
            if (named && name && !std::filesystem::exists(clef_path, ignored)) {
                if (auto found = named.find(*name)) {
                    if (origins != nullptr) {
                        (*origins)[declaration.id] = found->origin;
                    }
                    return std::move(found->clef);
                }
                throw DocumentError(declared_at,
                                    "clef \"" + declaration.id + "\": " + clef_path.string() +
                                        ": no such file beside the score, and no clef \"" + *name +
                                        "\" in " + named.places);
            }
            try {
                auto clef = load_clef_file(clef_path);
                if (origins != nullptr) {
                    (*origins)[declaration.id] = clef_path.string();
                }
                return clef;
            } catch (const DocumentError& error) {
                // A missing or unreadable clef file is the score's fault too:
                // name both places.
                if (error.diagnostics().size() == 1 && error.diagnostics()[0].where.line == 0) {
                    throw DocumentError(declared_at, "clef \"" + declaration.id +
                                                         "\": " + clef_path.string() + ": " +
                                                         error.diagnostics()[0].message);
                }
                throw;
            }
        });
}

}  // namespace vibscore
