#include "client/picture_verbs.hpp"

#include <memory>
#include <optional>

#include "client/editor/daemon_link.hpp"
#include "client/editor/documents.hpp"
#include "client/editor/verbs.hpp"
#include "client/offline_verbs.hpp"
#include "client/pictures/clef_picture.hpp"
#include "client/pictures/staff_picture.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/document_error.hpp"

namespace vibscore::client {

namespace {

// What `vibscore show` draws: a score or a clef, and what the picture calls it.
struct Shown {
    std::optional<Score> score;
    std::optional<Clef> clef;
    std::string name;
};

Shown read_shown(const std::string& document, const ClefSearch& clefs) {
    const auto source = editor::classify_source(document);
    if (source.kind == editor::ScoreSource::Kind::file) {
        const auto text = read_document_file(document);
        if (document_kind(text, document) == DocumentKind::clef) {
            return {std::nullopt, read_clef(text, document),
                    std::filesystem::path(document).filename().string()};
        }
        return {read_score(text, document).score, std::nullopt, document};
    }
    try {
        return {editor::read_score_to_show(document), std::nullopt, document};
    } catch (const editor::DaemonError& error) {
        // Not a score vibscored has (or no vibscored): a clef of that name, by the clef rule.
        const auto lookup = clefs.lookup();
        if (auto found = lookup.find(document)) {
            return {std::nullopt, std::move(found->clef), document};
        }
        throw editor::DaemonError(error.name(), std::string(error.what()) + "; and no clef \"" +
                                                    document + "\" in " + lookup.places);
    }
}

}  // namespace

int show_picture(const std::string& document, const std::string& svg, const std::string& png,
                 const ClefSearch& clefs, std::ostream& out, std::ostream& err) {
    try {
        for (const auto& path : {svg, png}) {
            if (!path.empty()) {
                pictures::picture_format_for(path);
            }
        }
    } catch (const std::invalid_argument& error) {
        err << "show: " << error.what() << "\n";
        return exit_usage;
    }
    try {
        const Shown shown = read_shown(document, clefs);
        std::unique_ptr<pictures::Drawing> picture;
        if (shown.clef) {
            picture = std::make_unique<pictures::ClefPicture>(*shown.clef, shown.name);
        } else {
            picture = std::make_unique<pictures::StaffPicture>(*shown.score);
        }
        for (const auto& path : {svg, png}) {
            if (!path.empty()) {
                pictures::write_picture(*picture, path);
                out << "wrote " << path << " (" << picture->width() << "x" << picture->height()
                    << ")\n";
            }
        }
        return exit_ok;
    } catch (const DocumentError& error) {
        err << error.what() << "\n";
    } catch (const editor::DaemonError& error) {
        err << "vibscore: " << error.what() << "\n";
    } catch (const std::exception& error) {
        err << "show: " << error.what() << "\n";
    }
    return exit_failed;
}

}  // namespace vibscore::client
