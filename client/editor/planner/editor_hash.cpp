#include "client/editor/planner/editor_hash.hpp"

#include <functional>

namespace vibscore::editor {

namespace {

void add_number(std::string& text, long long value) {
    text += std::to_string(value);
    text += ',';
}

}  // namespace

std::string score_text(const Score& score) {
    std::string text = score.version + '/' + score.title + '/';
    for (const auto& clef : score.clefs) {
        text += clef.id + '=' + clef.href + ';';
    }
    for (const auto& bar : score.bars) {
        text += '|' + bar.clef + ':';
        for (const auto& symbol : bar.symbols) {
            if (const auto* note = std::get_if<Note>(&symbol)) {
                text += 'N';
                add_number(text, static_cast<int>(note->length));
                add_number(text, note->number);
                add_number(text, note->string);
                add_number(text, static_cast<int>(note->dynamics));
                add_number(text, note->legato);
                add_number(text, note->portamento);
            } else if (const auto* rest = std::get_if<Rest>(&symbol)) {
                text += 'R';
                add_number(text, static_cast<int>(rest->length));
            } else {
                text += 'B';
            }
        }
    }
    return text;
}

std::size_t EditorHash::operator()(const Editor& editor) const {
    const auto& model = editor.model;
    std::string text = score_text(model.score());
    add_number(text, static_cast<long long>(model.cursor().bar));
    add_number(text, static_cast<long long>(model.cursor().symbol));
    add_number(text, model.string());
    add_number(text, static_cast<int>(model.current_length()));
    add_number(text, model.current_number());
    add_number(text, static_cast<int>(editor.scheme.mode()));
    add_number(text, static_cast<int>(editor.scheme.entry_step()));
    return std::hash<std::string>{}(text);
}

}  // namespace vibscore::editor
