#include <cstdio>

#include "client/editor/button_scheme.hpp"
#include "client/formats/score_builder.hpp"
#include "score/clef_xml.hpp"
#include "score/registry_names.hpp"

// Tapping a rhythm: Select taps a note, Down a rest; Up or Back ends tapping and writes the
// rhythm, Left drops it. Presses without a time (the press planner's) tap nothing.
namespace vibscore::editor {

Request ButtonScheme::tap_rhythm(EditorModel& model) {
    taps_ = {};
    mode_ = Mode::tapping;
    model.clear_message();
    return {};
}

Request ButtonScheme::tap_note(Button, EditorModel&, std::optional<Time> at) {
    if (at) {
        taps_.press_select(*at);
    }
    return {};
}

Request ButtonScheme::tap_rest(Button, EditorModel&, std::optional<Time> at) {
    if (at) {
        taps_.press_rest(*at);
    }
    return {};
}

Request ButtonScheme::finish_tapping(Button, EditorModel& model, std::optional<Time> at) {
    if (at) {
        taps_.finish(*at);
    }
    return end_tapping(model);
}

Request ButtonScheme::drop_tapping(Button, EditorModel& model, std::optional<Time>) {
    taps_ = {};
    mode_ = Mode::browse;
    model.say("tapping dropped");
    return {};
}

std::string ButtonScheme::tapping_hint(const EditorModel&) const {
    // Counted as they come, so a person sees each tap taken.
    const int tapped = taps_.taps();
    const std::string count = tapped == 0   ? "tap"
                              : tapped == 1 ? "1 tap"
                                            : std::to_string(tapped) + " taps";
    return count + " S:note \u2193rest \u2191 B:done \u2190drop";
}

// A rhythm tapped at another pace than its bar's clef plays at that pace: on a copy of the
// clef at the tapped tempo, named as the importers name theirs (lra-phone-150bpm), made once
// and found again when another rhythm is tapped at that tempo.
Request ButtonScheme::end_tapping(EditorModel& model) {
    mode_ = Mode::browse;
    const auto sounds = taps_.sounds();
    taps_ = {};
    if (sounds.empty()) {
        model.say("nothing tapped");
        return {};
    }
    const std::string& clef = model.score().bars.at(model.cursor().bar).clef;
    const KnownClef* known = clef_book_->find(clef);
    const double clef_tempo = known ? known->clef.tempo : 0.0;
    const Note proposed = model.proposed_note();
    try {
        auto rhythm = tapped_rhythm(sounds, clef_tempo, clef, proposed.string, proposed.number);
        char tempo[32];
        std::snprintf(tempo, sizeof tempo, "%.2f", rhythm.tempo);
        std::string said = std::to_string(rhythm.notes) + " notes at " + tempo + " s a beat";
        Request request;
        if (known != nullptr && rhythm.tempo != clef_tempo) {
            Clef copy = known->clef;
            copy.tempo = rhythm.tempo;
            std::string id =
                formats::clef_id_for({known->declaration.id, known->clef}, rhythm.tempo);
            // A copy made before (perhaps under a free name, beside another clef of this name).
            const KnownClef* found = clef_book_->find(id);
            for (const auto& each : clef_book_->clefs()) {
                if (each.clef == copy && each.declaration.id.starts_with(id)) {
                    found = &each;
                    id = each.declaration.id;
                    break;
                }
            }
            if (found == nullptr || found->clef != copy) {
                if (found != nullptr) {
                    std::vector<std::string> names;
                    for (const auto& each : clef_book_->clefs()) {
                        names.push_back(each.declaration.id);
                    }
                    id = free_name(id, names);
                }
                const ClefDeclaration declaration{id, id + std::string(kClefSuffix)};
                add_clef({declaration, copy, false});
                request = {Request::Kind::store_clef, id};
                request.document = write_clef(copy);
            }
            model.add_available_clef(clef_book_->find(id)->declaration);
            for (auto& bar : rhythm.bars) {
                bar.clef = id;
            }
            // The clef first: on a 40-column line the tempo it plays at is what must show.
            said = std::to_string(rhythm.notes) + " notes, clef " + id + " (" + tempo + " s)";
        } else {
            said += ": S changes";
        }
        model.insert_bars(rhythm.bars);
        model.say(said);
        return request;
    } catch (const std::exception& error) {
        model.say(std::string("not tapped: ") + error.what());
    }
    return {};
}

}  // namespace vibscore::editor
