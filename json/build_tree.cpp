#include "json/build_tree.hpp"

#include <cstdlib>

#include "config.h"
#include "json/json_document.hpp"

namespace vibscore {

namespace fs = std::filesystem;

std::optional<fs::path> source_tree_of(const fs::path& program) {
    std::error_code ignored;
    for (auto folder = program.parent_path(); !folder.empty(); folder = folder.parent_path()) {
        const auto info = folder / "meson-info" / "meson-info.json";
        if (fs::is_regular_file(info, ignored)) {
            try {
                const JsonDocument document = read_json_file(info.string());
                const JsonValue* directories = document.root().find("directories");
                const JsonValue* source =
                    directories == nullptr ? nullptr : directories->find("source");
                if (source == nullptr || source->kind != JsonValue::Kind::string ||
                    source->text.empty()) {
                    return std::nullopt;
                }
                return fs::path(source->text);
            } catch (const DocumentError&) {
                return std::nullopt;  // not meson's file after all: treated as installed
            }
        }
        if (folder == folder.root_path()) {
            break;
        }
    }
    return std::nullopt;
}

DataLocations installed_data() {
    return {VIBSCORE_CLEFDIR, VIBSCORE_FEEDBACK_THEME, VIBSCORE_CLIENT_DOCDIR};
}

DataLocations data_locations_of(const fs::path& program) {
    DataLocations found = installed_data();
    const auto source = source_tree_of(program);
    if (!source) {
        return found;
    }
    std::error_code ignored;
    if (const auto clefs = *source / "clefs"; fs::is_directory(clefs, ignored)) {
        found.clefs = clefs;
    }
    if (const auto theme = *source / "feedback" / "themes" / "default.json";
        fs::is_regular_file(theme, ignored)) {
        found.feedback_theme = theme;
    }
    if (const auto docs = *source / "docs"; fs::is_directory(docs, ignored)) {
        found.docs = docs;
    }
    return found;
}

DataLocations data_locations() {
    std::error_code error;
    const auto program = fs::read_symlink("/proc/self/exe", error);
    return error ? installed_data() : data_locations_of(program);
}

fs::path shipped_clefs_folder() {
    return data_locations().clefs;
}

fs::path default_feedback_theme(const DataLocations& located) {
    const char* chosen = std::getenv("FEEDBACK_THEME");
    if (chosen != nullptr && *chosen != '\0') {
        return chosen;
    }
    return located.feedback_theme;
}

}  // namespace vibscore
