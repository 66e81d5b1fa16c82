#include "client/editor/status_line.hpp"

#include <algorithm>
#include <cctype>

#include "client/editor/editor_model.hpp"
#include "client/editor/score_edits.hpp"

namespace vibscore::editor {

int columns_of(const std::string& text) {
    int columns = 0;
    for (const char c : text) {
        columns += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
    }
    return columns;
}

std::string fit(std::string text, int width) {
    int columns = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const bool starts_character = (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80;
        if (starts_character && ++columns > width) {
            text.resize(i);
            break;
        }
    }
    return text;
}

std::string status_line(const StatusParts& parts, int width) {
    std::string line = parts.modified ? "*" : "";
    if (!parts.message.empty()) {
        return fit(line + parts.message, width);
    }
    const std::string with_symbol = line + parts.entering + " " + parts.hint;
    line = !parts.entering.empty() && columns_of(with_symbol) <= width ? with_symbol
                                                                       : line + parts.hint;
    const std::string bar = "bar " + std::to_string(parts.bar) + "/" + std::to_string(parts.bars);
    const int room = width - columns_of(line);
    if (parts.bars > 0 && room >= columns_of(bar) + 1) {
        line += std::string(static_cast<std::size_t>(room - columns_of(bar)), ' ') + bar;
    }
    return fit(line, width);
}

std::string keyboard_hint() {
    return "keys: 1-9 note 0 rest  Shift+1..0 length whole..32nd  . dot  Space play";
}

namespace {

// Capitals: the same width, so the line still fits, and unlike every other word on it.
std::string shouted(std::string text, bool shout) {
    if (shout) {
        std::transform(text.begin(), text.end(), text.begin(),
                       [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    }
    return text;
}

}  // namespace

std::string symbol_words(const Symbol& symbol) {
    if (const auto* note = std::get_if<Note>(&symbol)) {
        return length_words(note->length) + ", " + std::to_string(note->number) + ", string " +
               std::to_string(note->string);
    }
    if (const auto* rest = std::get_if<Rest>(&symbol)) {
        return length_words(rest->length) + " rest";
    }
    return "blank";
}

std::string symbol_entered(const EditorModel& model) {
    const Symbol* symbol = symbol_at(model.score(), model.cursor());
    if (symbol == nullptr) {
        return "";
    }
    const auto unlike = model.unlike_last_entered();
    if (const auto* note = std::get_if<Note>(symbol)) {
        return std::to_string(note->number) + " " +
               shouted(length_words(note->length), unlike.length) + " " +
               shouted("s" + std::to_string(note->string), unlike.string);
    }
    if (const auto* rest = std::get_if<Rest>(symbol)) {
        return "rest " + shouted(length_words(rest->length), unlike.length);
    }
    return "";
}

}  // namespace vibscore::editor
