#include "client/clef_verbs.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "client/offline_verbs.hpp"
#include "score/clef_xml.hpp"
#include "score/document_error.hpp"
#include "score/registry_names.hpp"

namespace vibscore::client {

namespace {

// XML comments may not hold "--".
std::string comment_safe(std::string text) {
    for (std::size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at)) {
        text.replace(at, 2, "- -");
    }
    return text;
}

// Written whole or not at all: a temporary file beside it, renamed over it.
void write_whole(const std::filesystem::path& path, const std::string& text) {
    const std::filesystem::path temporary = path.string() + ".tmp";
    {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        if (!file || !(file << text) || !file.flush()) {
            const int error = errno;
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(error));
        }
    }
    std::error_code failed;
    std::filesystem::rename(temporary, path, failed);
    if (failed) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw std::runtime_error(path.string() + ": cannot write: " + failed.message());
    }
}

}  // namespace

FoundClef find_clef(const std::string& argument, const ClefSearch& clefs) {
    std::error_code ignored;
    if (std::filesystem::is_regular_file(argument, ignored)) {
        return {load_clef_file(argument), argument};
    }
    std::string name = argument;
    for (const std::string_view suffix : {kClefSuffix, std::string_view(".xml")}) {
        if (name.ends_with(suffix)) {
            name.erase(name.size() - suffix.size());
            break;
        }
    }
    const auto lookup = clefs.lookup();
    if (name.find('/') == std::string::npos) {
        if (auto found = lookup.find(name)) {
            return {std::move(found->clef), found->origin};
        }
    }
    throw DocumentError({argument, 0, 0},
                        "no such clef file, and no clef \"" + name + "\" in " + lookup.places);
}

std::string fitted_document(const render::ClefFit& fit, const std::string& written,
                            const actuator::Declaration& declaration) {
    std::string document = write_clef(fit.clef);
    std::string comment = "<!-- " +
                          comment_safe("Fitted by vibscore clef fit from " + written + " to " +
                                       actuator::describe(declaration)) +
                          ". -->\n";
    if (fit.notes.empty()) {
        comment += "<!-- It fits as written. -->\n";
    }
    for (const auto& note : fit.notes) {
        comment += "<!-- " + comment_safe(note) + " -->\n";
    }
    const auto declaration_end = document.find("?>\n");
    document.insert(declaration_end == std::string::npos ? 0 : declaration_end + 3, comment);
    return document;
}

int fit_clef_document(const ClefFitRequest& request, const ClefSearch& clefs, std::ostream& out,
                      std::ostream& err) {
    try {
        const FoundClef found = find_clef(request.clef, clefs);
        const render::ClefFit fit = render::fit_clef(found.clef, request.actuator);
        const std::string document = fitted_document(fit, request.clef, request.actuator);
        if (request.output.empty()) {
            out << document;
        } else {
            write_whole(request.output, document);
        }
        const std::string to = " to " + actuator::describe(request.actuator);
        if (fit.notes.empty()) {
            err << request.clef << ": fits" << to << " as written\n";
        } else {
            err << request.clef << ": fitted" << to << " (" << render::to_string(fit.strings)
                << ")\n";
            for (const auto& note : fit.notes) {
                err << request.clef << ": " << note << "\n";
            }
        }
        return exit_ok;
    } catch (const DocumentError& error) {
        for (const auto& diagnostic : error.diagnostics()) {
            err << format(diagnostic) << "\n";
        }
    } catch (const render::ClefFitError& error) {
        err << request.clef << ": cannot fit: " << error.what() << "\n";
    } catch (const std::runtime_error& error) {
        err << "vibscore: " << error.what() << "\n";
    }
    return exit_failed;
}

}  // namespace vibscore::client
