#include "client/formats/rtttl.hpp"

#include <algorithm>
#include <cctype>
#include <optional>

#include "client/formats/grid_fit.hpp"
#include "score/limits.hpp"
#include "score/line_index.hpp"
#include "score/xml_support.hpp"

namespace vibscore::formats {

namespace {

constexpr std::size_t kMaxNameChars = 64;
constexpr int kMaxBpm = 900;
constexpr int kMaxLoops = 15;  // RTX: 15 loops for ever

// RTX's styles: how notes that follow one another join.
enum class Style {
    natural,     // the renderer's default silence between notes
    continuous,  // no silence: tied by legato
    staccato,    // each note sounds half its length, a rest the other half
};

struct Parsed {
    std::string name;
    int bpm = 63;  // the format's defaults
    int loops = 0;
    struct Tone {
        std::int64_t ticks = 0;
        std::optional<double> pitch;  // semitones (MIDI numbering); none for a pause
        Style style = Style::natural;
    };
    std::vector<Tone> tones;
    std::vector<TempoChange> tempi;  // from tick 0, in 32nds of the score's grid
};

class RtttlParser {
  public:
    RtttlParser(std::string_view text, const LineIndex& lines, DiagnosticSink& sink)
        : text_(text), lines_(lines), sink_(sink) {}

    Parsed parse() {
        Parsed parsed;
        const auto first_colon = text_.find(':');
        const auto second_colon =
            first_colon == std::string_view::npos ? first_colon : text_.find(':', first_colon + 1);
        if (second_colon == std::string_view::npos) {
            report(0, "an RTTTL text is NAME:DEFAULTS:NOTES, e.g. tune:d=4,o=5,b=120:c,e,g");
            return parsed;
        }
        parsed.name = std::string(trim(text_.substr(0, first_colon)));
        if (parsed.name.size() > kMaxNameChars) {
            report(0, "the name is longer than " + std::to_string(kMaxNameChars) + " characters");
        }
        for_each_item(first_colon + 1, second_colon,
                      [&](std::size_t offset, std::string_view item) {
                          read_control(offset, item, parsed, false);
                      });
        parsed.tempi.push_back({0, 60.0 / parsed.bpm});
        read_notes(second_colon + 1, parsed);
        return parsed;
    }

  private:
    void report(std::size_t offset, const std::string& message) {
        sink_.report(lines_.at(static_cast<std::ptrdiff_t>(offset)), message);
    }

    static std::string_view trim(std::string_view text) {
        while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) {
            text.remove_prefix(1);
        }
        while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
            text.remove_suffix(1);
        }
        return text;
    }

    static char lower(char c) {
        return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }

    // Splits [begin, end) at commas, calling each(offset of the trimmed item, item).
    template <typename Each>
    void for_each_item(std::size_t begin, std::size_t end, Each&& each) {
        while (begin < end) {
            std::size_t comma = text_.find(',', begin);
            if (comma == std::string_view::npos || comma > end) {
                comma = end;
            }
            std::size_t start = begin;
            while (start < comma && std::isspace(static_cast<unsigned char>(text_[start]))) {
                ++start;
            }
            const auto item = trim(text_.substr(start, comma - start));
            if (!item.empty()) {
                each(start, item);
            } else if (comma < end) {
                report(start, "an empty item between commas");
            }
            begin = comma + 1;
        }
    }

    // A whole number of up to four digits at the front of `item`, removed from it.
    static std::optional<int> take_number(std::string_view& item) {
        std::size_t digits = 0;
        while (digits < item.size() && std::isdigit(static_cast<unsigned char>(item[digits]))) {
            ++digits;
        }
        if (digits == 0 || digits > 4) {
            return std::nullopt;
        }
        const int value = std::stoi(std::string(item.substr(0, digits)));
        item.remove_prefix(digits);
        return value;
    }

    static bool valid_duration(int duration) {
        return duration == 1 || duration == 2 || duration == 4 || duration == 8 || duration == 16 ||
               duration == 32;
    }

    // An RTX control pair, NAME[=]VALUE: d (duration), o (octave), b (beats per minute), s
    // (style N, C or S), l (loops, 0 to 15). In the defaults any other name is ignored, as RTX
    // asks; among the notes o, b and s may change what follows (b and d only with "=", since
    // "b" alone is a note).
    void read_control(std::size_t offset, std::string_view item, Parsed& parsed, bool among_notes) {
        const char name = lower(item.front());
        auto value = trim(item.substr(1));
        if (!value.empty() && value.front() == '=') {
            value = trim(value.substr(1));
        }
        const std::string shown(item);
        if (name == 's') {
            const char style = value.size() == 1 ? lower(value.front()) : '\0';
            if (style == 'n' || style == 'c' || style == 's') {
                style_ = style == 'n' ? Style::natural
                                      : (style == 'c' ? Style::continuous : Style::staccato);
            } else {
                report(offset, "\"" + shown +
                                   "\": the style is N (natural), C (continuous) or S "
                                   "(staccato)");
            }
            return;
        }
        if (name != 'd' && name != 'o' && name != 'b' && name != 'l') {
            if (among_notes) {
                report(offset, "\"" + shown + "\" is neither a note nor o=, b= or s=");
            }
            return;  // RTX: unknown control names are ignored
        }
        auto digits = value;
        const auto number = take_number(digits);
        if (!number || !digits.empty()) {
            report(offset, "\"" + shown + "\" is not " + std::string(1, name) + "= with a number");
            return;
        }
        if (name == 'd' && valid_duration(*number) && !among_notes) {
            duration_ = *number;
        } else if (name == 'o' && *number <= 9) {
            octave_ = *number;
        } else if (name == 'b' && *number >= 1 && *number <= kMaxBpm) {
            if (among_notes) {
                parsed.tempi.push_back({ticks_, 60.0 / *number});
            } else {
                parsed.bpm = *number;
            }
            bpm_ = *number;
        } else if (name == 'l' && *number <= kMaxLoops && !among_notes) {
            parsed.loops = *number;
        } else if (among_notes && (name == 'd' || name == 'l')) {
            report(offset, "\"" + shown + "\": among the notes only o=, b= and s= may change");
        } else {
            report(offset, "\"" + shown +
                               "\" is out of range (d: 1, 2, 4, 8, 16, 32; o: 0 to 9; b: 1 to "
                               "900; l: 0 to 15)");
        }
    }

    void read_notes(std::size_t begin, Parsed& parsed) {
        for_each_item(begin, text_.size(), [&](std::size_t offset, std::string_view item) {
            if (past_limits_) {
                return;
            }
            const char first = lower(item.front());
            const bool control = first == 'o' || first == 's' ||
                                 ((first == 'b' || first == 'd' || first == 'l') &&
                                  trim(item.substr(1)).starts_with('='));
            if (control) {
                read_control(offset, item, parsed, true);
            } else {
                read_note(offset, item, parsed);
            }
        });
        if (parsed.tones.empty()) {
            report(begin, "no notes after the second colon");
        }
    }

    // [duration] letter [# or _] [.] [octave] [.]: "_" is a flat, and the dot may come before
    // or after the octave, as collections write both.
    void read_note(std::size_t offset, std::string_view item, Parsed& parsed) {
        const std::string original(item);
        const auto bad = [&](const std::string& why) {
            report(offset, "note \"" + original + "\": " + why);
        };
        int duration = duration_;
        if (std::isdigit(static_cast<unsigned char>(item.front()))) {
            const auto read = take_number(item);
            if (!read || !valid_duration(*read)) {
                bad("the duration is 1, 2, 4, 8, 16 or 32");
                return;
            }
            duration = *read;
        }
        if (item.empty()) {
            bad("no note letter");
            return;
        }
        static constexpr std::string_view kLetters = "cdefgab";
        static constexpr int kSemitones[] = {0, 2, 4, 5, 7, 9, 11};
        const char letter = lower(item.front());
        item.remove_prefix(1);
        std::optional<int> semitone;
        if (letter == 'h') {
            semitone = 11;  // the German B some ringtones use
        } else if (const auto found = kLetters.find(letter); found != std::string_view::npos) {
            semitone = kSemitones[found];
        } else if (letter != 'p') {
            bad("the note letter is a to g, or p for a pause");
            return;
        }
        if (!item.empty() && (item.front() == '#' || item.front() == '_')) {
            if (!semitone) {
                bad(item.front() == '#' ? "a pause cannot be sharp" : "a pause cannot be flat");
                return;
            }
            *semitone += item.front() == '#' ? 1 : -1;
            item.remove_prefix(1);
        }
        bool dotted = false;
        if (!item.empty() && item.front() == '.') {
            dotted = true;
            item.remove_prefix(1);
        }
        int octave = octave_;
        if (!item.empty() && std::isdigit(static_cast<unsigned char>(item.front()))) {
            octave = item.front() - '0';
            item.remove_prefix(1);
        }
        if (!item.empty() && item.front() == '.' && !dotted) {
            dotted = true;
            item.remove_prefix(1);
        }
        if (!item.empty()) {
            bad("unexpected \"" + std::string(item) + "\" after the note");
            return;
        }
        // A note of duration d lasts 4/d quarter notes: 32 ticks / d on the score's grid.
        std::int64_t ticks = 4 * ticks_per_quarter / duration;
        if (dotted) {
            if (ticks % 2 != 0) {
                bad("a dotted 32nd lasts 3/16 of a beat, finer than a score's 32nd-note grid");
                return;
            }
            ticks += ticks / 2;
        }
        if (!within_limits(offset, ticks, parsed)) {
            return;
        }
        Parsed::Tone tone{ticks, std::nullopt, style_};
        if (semitone) {
            tone.pitch = 12.0 * (octave + 1) + *semitone;
        }
        parsed.tones.push_back(tone);
    }

    // A score's limits, checked note by note so that a long text is refused where it passes
    // them, with no more work than reading up to there.
    bool within_limits(std::size_t offset, std::int64_t ticks, const Parsed& parsed) {
        ticks_ += ticks;
        seconds_ += static_cast<double>(ticks) * 60.0 / bpm_ / ticks_per_quarter;
        std::string broken;
        if (parsed.tones.size() == limits::symbols) {
            broken = "more than " + std::to_string(limits::symbols) +
                     " notes and pauses; a score holds at most " + std::to_string(limits::symbols) +
                     " symbols";
        } else if (ticks_ > max_import_ticks) {
            broken = "the tune passes " + std::to_string(max_import_ticks / ticks_per_quarter) +
                     " beats here; a score holds at most " + std::to_string(limits::bars) +
                     " bars of four beats";
        } else if (past_the_hour(seconds_)) {
            broken = "the tune passes " + xml::format_number(limits::max_score_seconds) +
                     " s here; a score lasts at most " +
                     xml::format_number(limits::max_score_seconds) + " s";
        }
        if (broken.empty()) {
            return true;
        }
        report(offset, "too long for a score: " + broken);
        past_limits_ = true;
        return false;
    }

    std::string_view text_;
    const LineIndex& lines_;
    DiagnosticSink& sink_;
    int duration_ = 4;
    int octave_ = 6;
    int bpm_ = 63;
    Style style_ = Style::natural;
    std::int64_t ticks_ = 0;
    double seconds_ = 0.0;
    bool past_limits_ = false;
};

}  // namespace

ImportedScore read_rtttl(std::string_view text, const std::string& file, const ChosenClef& chosen) {
    check_document_size(text, file);
    const LineIndex lines(text, file);
    DiagnosticSink sink;
    RtttlParser parser(text, lines, sink);
    const auto parsed = parser.parse();
    sink.throw_if_any();

    std::vector<double> pitches;
    for (const auto& tone : parsed.tones) {
        if (tone.pitch) {
            pitches.push_back(*tone.pitch);
        }
    }
    const auto strings = strings_by_contour(pitches, static_cast<int>(chosen.clef.strings.size()));
    const int strongest = nearest_number(chosen.clef, 1.0);
    std::vector<GridNote> notes;
    std::int64_t now = 0;
    std::size_t pitched = 0;
    for (const auto& tone : parsed.tones) {
        if (tone.pitch) {
            GridNote note;
            note.start = now;
            note.length = tone.ticks;
            note.string = strings[pitched++];
            note.number = strongest;
            if (tone.style == Style::staccato) {
                note.length = (tone.ticks + 1) / 2;  // the rest of the note is silence
            } else if (tone.style == Style::continuous) {
                note.tie_to_next = GridNote::Tie::legato;  // kept when the next note touches
            }
            notes.push_back(note);
        }
        now += tone.ticks;
    }
    return build_score(notes, parsed.tempi, now, chosen, parsed.name, file);
}

}  // namespace vibscore::formats
