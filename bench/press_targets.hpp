#pragma once

// What bench/editor_presses and bench/editor_presses_oracle enter and learn from: the thesis'
// Fig. 2.3 measure, the shipped notification set, the thesis' tactons, and a registry folder
// of .score.xml files. One definition, so the bound and the count measure the same sets.

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "client/editor/phrase_book.hpp"
#include "score/bundle.hpp"
#include "score/score_xml.hpp"

namespace vibscore::bench {

// Thesis Fig. 2.3a, first measure: an 8th (string 2, number 1) tied by legato to a quarter
// (string 3, number 2), an 8th rest and a half note (string 1, number 2); as the repository's
// golden tests write it.
inline constexpr const char* kFigure23 =
    "<VibScore><Title>Fig. 2.3 first measure</Title>"
    "<Clef id=\"c\" href=\"fig23-sine.clef.xml\"/><Bar clef=\"c\">"
    "<Note length=\"8th\" number=\"1\" string=\"2\" legato=\"1\"/>"
    "<Note length=\"quarter\" number=\"2\" string=\"3\" legato=\"1\"/>"
    "<Rest length=\"8th\"/><Note length=\"half\" number=\"2\" string=\"1\"/>"
    "</Bar></VibScore>";

// The shipped notification set (phone LRA) and the thesis' tactons (Figs. 5.1 and 5.2).
inline const std::vector<std::string> kNotifications{
    "alarm",    "failure", "notification-calendar", "notification-mail", "notification-message",
    "ringtone", "success", "touch-click",           "touch-tick"};
inline const std::vector<std::string> kThesisTactons{"create",      "delete",
                                                     "file",        "folder",
                                                     "create-file", "create-folder",
                                                     "delete-file", "delete-folder",
                                                     "call",        "call-high-priority",
                                                     "message",     "message-high-priority"};

struct Tacton {
    std::string name;         // the file name without .score.xml
    editor::NamedScore file;  // by its file name: the leave-one-out compares it with the registry's
};

inline Tacton read_tacton(const std::filesystem::path& path) {
    std::string name = path.filename().string();
    const std::string_view suffix = ".score.xml";
    if (name.ends_with(suffix)) {
        name.resize(name.size() - suffix.size());
    }
    return {name,
            {path.filename().string(), read_score(read_document_file(path), path.string()).score}};
}

// The .score.xml files of a folder, by name; a file stands for itself.
inline std::vector<std::filesystem::path> score_files(const std::filesystem::path& path) {
    if (!std::filesystem::is_directory(path)) {
        return {path};
    }
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(path)) {
        if (entry.path().filename().string().ends_with(".score.xml")) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

// Every score the registry folder holds; one that does not read is left out, and said so.
inline std::vector<editor::NamedScore> read_registry(const std::filesystem::path& folder) {
    std::vector<editor::NamedScore> registry;
    for (const auto& file : score_files(folder)) {
        try {
            registry.push_back(read_tacton(file).file);
        } catch (const std::exception& error) {
            std::cerr << "registry: left out: " << error.what() << "\n";
        }
    }
    return registry;
}

}  // namespace vibscore::bench
