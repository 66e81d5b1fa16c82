#include "client/clef_search.hpp"

#include <nlohmann/json.hpp>

#include <fstream>

#include "config.h"
#include "score/clef_xml.hpp"
#include "score/registry_names.hpp"

namespace vibscore::client {

std::optional<std::filesystem::path> source_tree_clefs(const std::filesystem::path& program) {
    std::error_code ignored;
    for (auto folder = program.parent_path(); !folder.empty() && folder != folder.root_path();
         folder = folder.parent_path()) {
        const auto info = folder / "meson-info" / "meson-info.json";
        if (!std::filesystem::is_regular_file(info, ignored)) {
            continue;
        }
        std::ifstream in(info);
        const auto json = nlohmann::json::parse(in, nullptr, false);
        if (json.is_discarded() || !json.contains("directories") ||
            !json["directories"].contains("source") || !json["directories"]["source"].is_string()) {
            return std::nullopt;
        }
        const auto clefs =
            std::filesystem::path(json["directories"]["source"].get<std::string>()) / "clefs";
        if (!std::filesystem::is_directory(clefs, ignored)) {
            return std::nullopt;
        }
        return clefs;
    }
    return std::nullopt;
}

std::filesystem::path shipped_clefs_folder() {
    std::error_code error;
    const auto program = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        if (auto clefs = source_tree_clefs(program)) {
            return *clefs;
        }
    }
    return VIBSCORE_CLEFDIR;
}

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

}  // namespace vibscore::client
