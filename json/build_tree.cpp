#include "json/build_tree.hpp"

#include "json/json_document.hpp"
#include "config.h"

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

fs::path shipped_clefs_folder() {
    std::error_code error;
    const auto program = fs::read_symlink("/proc/self/exe", error);
    if (!error) {
        if (const auto source = source_tree_of(program)) {
            const auto clefs = *source / "clefs";
            if (fs::is_directory(clefs, error)) {
                return clefs;
            }
        }
    }
    return VIBSCORE_CLEFDIR;
}

}  // namespace vibscore
