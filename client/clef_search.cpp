#include "client/clef_search.hpp"

#include "json/build_tree.hpp"
#include "score/clef_xml.hpp"
#include "score/registry_names.hpp"
#include "score/score_xml.hpp"

namespace vibscore::client {

ClefSearch::ClefSearch() : shipped(shipped_clefs_folder()) {}

NamedClefLookup ClefSearch::lookup() const {
    std::string places;
    for (const auto& folder : folders) {
        places += folder.string() + ", ";
    }
    if (registry) {
        places += "vibscored's registry, ";
    }
    places += shipped.string() + " (--clefs DIR looks in a folder of your own first)";
    const auto find = [search = *this](const std::string& name) -> std::optional<NamedClef> {
        const std::string file_name = name + std::string(kClefSuffix);
        const auto from_folder =
            [&](const std::filesystem::path& folder) -> std::optional<NamedClef> {
            const auto path = folder / file_name;
            std::error_code ignored;
            if (folder.empty() || !std::filesystem::is_regular_file(path, ignored)) {
                return std::nullopt;
            }
            return NamedClef{load_clef_file(path), path.string()};
        };
        for (const auto& folder : search.folders) {
            if (auto found = from_folder(folder)) {
                return found;
            }
        }
        if (search.registry) {
            if (const auto text = search.registry(name)) {
                return NamedClef{read_clef(*text, "registry clef \"" + name + "\""),
                                 kRegistryOrigin};
            }
        }
        return from_folder(search.shipped);
    };
    return {find, places};
}

LoadedScore load_score(const std::filesystem::path& path, const ClefSearch& search) {
    LoadedScore loaded;
    loaded.bundle = load_score_file(path, search.lookup(), &loaded.clef_origins);
    return loaded;
}

bool names_a_file(const std::string& argument) {
    std::error_code ignored;
    return argument.find('/') != std::string::npos || argument.ends_with(".xml") ||
           std::filesystem::is_regular_file(argument, ignored);
}

namespace {

// vibscored's score NAME bound to its clefs: each href a registry clef name, found by the rule.
LoadedScore registry_score(const std::string& name, const std::string& text,
                           const ClefSearch& search) {
    const std::string label = "registry score \"" + name + "\"";
    const auto lookup = search.lookup();
    LoadedScore loaded;
    loaded.bundle = bind_clefs(
        read_score(text, label), label,
        [&](const ClefDeclaration& declaration, const SourceLocation& where) {
            const auto clef = clef_name_in_href(declaration.href);
            if (!clef) {
                throw DocumentError(where,
                                    "href \"" + declaration.href + "\" names no registry clef");
            }
            auto found = lookup.find(*clef);
            if (!found) {
                throw DocumentError(where, "no clef \"" + *clef + "\" in " + lookup.places);
            }
            loaded.clef_origins[declaration.id] = found->origin;
            return std::move(found->clef);
        });
    return loaded;
}

}  // namespace

RegistryDocument load_registry_document(const std::string& name, const ClefSearch& search) {
    std::string why = "there is no vibscored to ask";
    if (search.registry_score) {
        std::optional<std::string> text;
        try {
            text = search.registry_score(name);
        } catch (const std::runtime_error& error) {
            why = error.what();
        }
        if (text) {
            return {registry_score(name, *text, search), std::nullopt};
        }
    }
    // Not a score vibscored has (or no vibscored): a clef of that name, by the clef rule.
    const auto lookup = search.lookup();
    if (auto found = lookup.find(name)) {
        return {std::nullopt, std::move(found->clef)};
    }
    throw std::runtime_error(name + ": no such file, no registry score of that name (" + why +
                             "), and no clef \"" + name + "\" in " + lookup.places);
}

}  // namespace vibscore::client
