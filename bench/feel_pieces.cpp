#include "bench/feel_pieces.hpp"

#include <cmath>
#include <utility>

#include "bench/feel_plant.hpp"
#include "daemon/render/cue_adaptation.hpp"
#include "daemon/render/cue_schedule.hpp"
#include "daemon/render/performance.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"

namespace vibscore::bench {

using actuator::Declaration;

const std::vector<std::string> kTactons{
    "alarm",    "failure", "notification-calendar", "notification-mail", "notification-message",
    "ringtone", "success", "touch-click",           "touch-tick"};

namespace {

// Ten 50 ms taps a second, and keystrokes while typing (25 ms clicks, 50-150 ms apart).
const char* const kTaps =
    "<VibScore><Title>ten taps a second</Title><Clef id=\"lra\" href=\"lra-phone.clef.xml\"/>"
    "<Bar clef=\"lra\">"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "<Note length=\"16th\" number=\"9\" string=\"6\"/><Rest length=\"16th\"/>"
    "</Bar></VibScore>";
const char* const kTyping =
    "<VibScore><Title>typing</Title><Clef id=\"lra\" href=\"lra-phone.clef.xml\"/>"
    "<Bar clef=\"lra\">"
    "<Note length=\"32th\" number=\"7\" string=\"5\"/><Rest length=\"16th_dot\"/>"
    "<Note length=\"32th\" number=\"7\" string=\"5\"/><Rest length=\"8th\"/>"
    "<Note length=\"32th\" number=\"8\" string=\"5\"/><Rest length=\"16th\"/>"
    "<Note length=\"32th\" number=\"7\" string=\"5\"/><Rest length=\"8th_dot\"/>"
    "<Note length=\"32th\" number=\"7\" string=\"5\"/><Rest length=\"16th\"/>"
    "<Note length=\"32th\" number=\"9\" string=\"5\"/><Rest length=\"8th\"/>"
    "</Bar></VibScore>";

// A sine clef's strings moved inside an LRA's band (where it gives more than 1/sqrt(2) of its
// strength: f0 +- f0/2Q), evenly, in their order: "a clef whose strings sit inside its band".
Clef inside_band(Clef clef, const Declaration& lra) {
    const double half_band = 0.9 * lra.resonance_hz / (2.0 * lra.q);
    const std::size_t n = clef.strings.size();
    for (std::size_t s = 0; s < n; ++s) {
        const double position = n > 1 ? static_cast<double>(s) / static_cast<double>(n - 1) : 0.5;
        clef.strings[s].frequency = lra.resonance_hz + (2.0 * position - 1.0) * half_band;
    }
    return clef;
}

std::vector<render::Cue> drives_for(const render::Performance& performance,
                                    const Declaration& declared, bool compensation,
                                    const render::Uncertainty& uncertainty) {
    render::CueAdaptation adaptation;
    adaptation.actuator = declared;
    adaptation.uncertainty = uncertainty;
    adaptation.actuator->compensation = compensation;
    adaptation.reverse = true;
    auto cues =
        render::adapt_cues(render::cue_schedule(performance), performance.duration(), adaptation);
    std::erase_if(cues,
                  [](const render::Cue& cue) { return cue.kind != render::Cue::Kind::drive; });
    return cues;
}

}  // namespace

std::vector<Piece> pieces(const std::filesystem::path& clefs) {
    std::vector<Piece> all;
    for (const auto& name : kTactons) {
        all.push_back({name, load_score_file(clefs / (name + ".score.xml"))});
    }
    const Clef lra_phone = load_clef_file(clefs / "lra-phone.clef.xml");
    for (const auto& [name, text] : {std::pair{"taps", kTaps}, std::pair{"typing", kTyping}}) {
        all.push_back({name, bind_clefs(read_score(text, name), name,
                                        [&](const ClefDeclaration&, const SourceLocation&) {
                                            return lra_phone;
                                        })});
    }
    return all;
}

ScoreBundle for_actuator(ScoreBundle bundle, const Declaration& declared) {
    if (declared.kind == actuator::Kind::lra) {
        for (auto& [id, clef] : bundle.clefs) {
            if (clef.type == ClefType::sine) {
                clef = inside_band(clef, declared);
            }
        }
    }
    return bundle;
}

ScoreFeel judge(const std::string& name, const std::vector<NoteSpan>& notes,
                const std::vector<double>& written, const std::vector<render::Cue>& drives,
                const Declaration& truth) {
    const Plant plant(truth);
    const auto produced = plant.respond(drives, kRate, written.size());
    // As if nothing more were sent from `t` (the next note's start): the drive in force then stops
    // there. Left on, a brake the next note cut short would go on braking for ever and spin an
    // ERM backwards, or push an LRA back up: no player does that.
    const auto produced_until = [&](double t) {
        std::vector<render::Cue> before;
        for (const auto& cue : drives) {
            if (cue.at < t) {
                before.push_back(cue);
            }
        }
        before.push_back(render::drive_at(t, 0.0, 0.0));
        return plant.respond(before, kRate, written.size());
    };
    return measure(name, notes, written, produced, produced_until, kRate);
}

ScoreFeel feel(const Piece& piece, const Declaration& declared, const Declaration& truth,
               bool compensation, const render::Uncertainty& uncertainty) {
    const render::Performance performance(for_actuator(piece.bundle, declared));
    const auto drives = drives_for(performance, declared, compensation, uncertainty);
    const auto count =
        static_cast<std::size_t>(std::ceil((performance.duration() + kTail) * kRate));
    std::vector<double> written;
    for (std::size_t k = 0; k < count; ++k) {
        written.push_back(performance.envelope_at(static_cast<double>(k) / kRate));
    }
    return judge(piece.name, note_spans(performance, 1.0), written, drives, truth);
}

}  // namespace vibscore::bench
