// Tapping a rhythm (client/editor/tap_rhythm.*): press and release times with a human's jitter
// in, notes and rests on the score's grid out.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <random>
#include <set>

#include "client/editor/tap_rhythm.hpp"
#include "daemon/render/performance.hpp"
#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::TapRecorder;
using Time = TapRecorder::Time;

Time at(double seconds) {
    return Time(static_cast<long long>(std::llround(seconds * 1e6)));
}

// ±20 ms, as a thumb keeps time.
class Jitter {
  public:
    explicit Jitter(unsigned seed) : random_(seed) {}
    double operator()(double t) { return t + spread_(random_); }

  private:
    std::mt19937 random_;
    std::uniform_real_distribution<double> spread_{-0.020, 0.020};
};

// Thesis Fig. 7.5 (Experiment 2's score task): three bars of four quarter notes, a quarter
// note lasting 0.8 s; on string 3 with number 5 here, the proposed note.
std::vector<Bar> figure_75() {
    std::string bars;
    for (int bar = 0; bar < 3; ++bar) {
        bars += "<Bar clef=\"lra\">";
        for (int note = 0; note < 4; ++note) {
            bars += "<Note length=\"quarter\" number=\"5\" string=\"3\"/>";
        }
        bars += "</Bar>";
    }
    return testing::bars(bars);
}

TEST(TappedRhythm, Figure75ComesBackExactlyFromPressesAndReleasesWithJitter) {
    for (unsigned seed = 1; seed <= 100; ++seed) {
        Jitter jitter(seed);
        TapRecorder taps;
        // Each note held until just before the next press: 100 ms to lift the thumb.
        for (int k = 0; k < 12; ++k) {
            taps.press_select(at(jitter(0.8 * k)));
            taps.release_select(at(jitter(0.8 * (k + 1) - 0.1)));
        }
        taps.finish(at(jitter(12.0)));  // a pause, then done: the release ended the last note
        const auto rhythm = editor::tapped_rhythm(taps.sounds(), 0.5, "lra", 3, 5);
        EXPECT_EQ(rhythm.bars, figure_75()) << "seed " << seed;
        EXPECT_NEAR(rhythm.tempo, 0.8, 0.02) << "seed " << seed;
        EXPECT_EQ(rhythm.notes, 12);
        EXPECT_EQ(rhythm.rests, 0);
    }
}

TEST(TappedRhythm, Figure75ComesBackExactlyFromATerminalsPressesAlone) {
    // A terminal sees no releases: the time to the next tap is the note; the done press ends the
    // last one (however late, no longer than the usual time between taps).
    for (unsigned seed = 1; seed <= 100; ++seed) {
        Jitter jitter(seed);
        TapRecorder taps;
        for (int k = 0; k < 12; ++k) {
            taps.press_select(at(jitter(0.8 * k)));
        }
        taps.finish(at(seed % 2 == 0 ? jitter(9.6) : 14.0));
        const auto rhythm = editor::tapped_rhythm(taps.sounds(), 0.5, "lra", 3, 5);
        EXPECT_EQ(rhythm.bars, figure_75()) << "seed " << seed;
    }
}

TEST(TappedRhythm, ReleasesLongEnoughAreRestsAndATapOnDownIsARest) {
    // At the clef's tempo, 0.5 s: quarter, quarter, 8th, 8th, quarter; a quarter, a quarter's
    // rest (let go) and an 8th's (tapped on Down), one dotted quarter rest together, and a
    // dotted quarter; quarter, quarter, half. The quarter is the most common time between taps.
    for (unsigned seed = 1; seed <= 100; ++seed) {
        Jitter jitter(seed);
        TapRecorder taps;
        const auto note = [&](double down, double up) {
            taps.press_select(at(jitter(down)));
            taps.release_select(at(jitter(up)));
        };
        note(0.0, 0.42);  // let go 80 ms before the next press: the thumb's silence
        note(0.5, 0.92);
        note(1.0, 1.17);
        note(1.25, 1.42);
        note(1.5, 1.92);
        note(2.0, 2.5);  // let go for a quarter: a rest
        taps.press_rest(at(jitter(3.0)));
        note(3.25, 3.92);
        note(4.0, 4.42);
        note(4.5, 4.92);
        note(5.0, 5.92);
        taps.finish(at(7.0));
        const auto rhythm = editor::tapped_rhythm(taps.sounds(), 0.5, "lra", 2, 7);
        EXPECT_DOUBLE_EQ(rhythm.tempo, 0.5) << "seed " << seed;  // the clef's own
        EXPECT_EQ(
            rhythm.bars,
            testing::bars("<Bar clef=\"lra\"><Note length=\"quarter\" number=\"7\" string=\"2\"/>"
                          "<Note length=\"quarter\" number=\"7\" string=\"2\"/>"
                          "<Note length=\"8th\" number=\"7\" string=\"2\"/>"
                          "<Note length=\"8th\" number=\"7\" string=\"2\"/>"
                          "<Note length=\"quarter\" number=\"7\" string=\"2\"/></Bar>"
                          "<Bar clef=\"lra\"><Note length=\"quarter\" number=\"7\" string=\"2\"/>"
                          "<Rest length=\"quarter_dot\"/>"
                          "<Note length=\"quarter_dot\" number=\"7\" string=\"2\"/></Bar>"
                          "<Bar clef=\"lra\"><Note length=\"quarter\" number=\"7\" string=\"2\"/>"
                          "<Note length=\"quarter\" number=\"7\" string=\"2\"/>"
                          "<Note length=\"half\" number=\"7\" string=\"2\"/></Bar>"))
            << "seed " << seed;
    }
}

TEST(TappedRhythm, AReleaseJustUnderTheShortestRestIsTheSilenceBetweenNotes) {
    // Two quarters at 1.2 s: a release of 0.14 s is the thumb lifting (under 0.15 s and a
    // quarter of the time), 0.31 s is a rest (both over).
    const auto two_taps = [](double release) {
        TapRecorder taps;
        taps.press_select(at(0.0));
        taps.release_select(at(1.2 - release));
        taps.press_select(at(1.2));
        taps.release_select(at(2.4 - release));
        return taps.sounds();
    };
    const auto held = two_taps(0.14);
    EXPECT_DOUBLE_EQ(held[0].end, 1.2);
    const auto rested = two_taps(0.31);
    EXPECT_NEAR(rested[0].end, 0.89, 1e-9);
    // The edge itself, max(0.15, 1.2 / 4 = 0.3): 0.3 is a rest, just under it is not.
    EXPECT_NEAR(two_taps(0.3)[0].end, 0.9, 1e-9);
    EXPECT_DOUBLE_EQ(two_taps(0.299)[0].end, 1.2);
    // At a fast pace the 0.15 s floor decides: 0.4 s apart, 0.15 is a rest, 0.149 is not.
    const auto fast = [](double release) {
        TapRecorder taps;
        taps.press_select(at(0.0));
        taps.release_select(at(0.4 - release));
        taps.press_select(at(0.4));
        return taps.sounds()[0].end;
    };
    EXPECT_NEAR(fast(0.15), 0.25, 1e-9);
    EXPECT_DOUBLE_EQ(fast(0.149), 0.4);
}

// Issue 31: a rhythm tapped at 0.25, 0.40 and 0.87 s a beat plays as long as it was tapped,
// and an interval tapped twice is written the same way wherever in the bar it falls.
// The rhythm in beats between taps: each length comes back at several places in the bars.
constexpr double kTappedBeats[] = {1, 1, 0.5, 0.5, 1, 2, 1, 0.5, 0.5, 1.5, 0.5, 1, 1, 2, 1, 1};

double rendered_seconds(const editor::TappedRhythm& rhythm) {
    ParsedScore parsed;
    parsed.score.title = "tapped";
    parsed.score.clefs.push_back({"lra", "lra-phone.clef.xml"});
    parsed.score.bars = rhythm.bars;
    parsed.where.clefs.resize(1);
    for (const auto& bar : rhythm.bars) {
        parsed.where.bars.emplace_back();
        parsed.where.symbols.emplace_back(bar.symbols.size());
    }
    const auto bundle = bind_clefs(std::move(parsed), "tapped", [&](const auto&, const auto&) {
        Clef clef;
        clef.tempo = rhythm.tempo;  // the tempo clef the editor makes for it
        clef.numbers = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
        clef.strings.resize(6, ClefString{150.0, {}});
        return clef;
    });
    return render::Performance(bundle).duration();
}

TEST(TappedRhythm, PlaysAsLongAsTappedAtThreeTemposAndWritesEachIntervalOneWay) {
    for (const double beat : {0.25, 0.40, 0.87}) {
        for (unsigned seed = 1; seed <= 50; ++seed) {
            Jitter jitter(seed);
            TapRecorder taps;
            double nominal = 0.0;
            std::vector<double> onsets;
            for (const double beats : kTappedBeats) {
                onsets.push_back(jitter(nominal));
                taps.press_select(at(onsets.back()));
                nominal += beats * beat;
            }
            const double done = jitter(nominal);
            taps.finish(at(done));
            // The bar clef's tempo is 0.2 s: none of these is at its pace.
            const auto rhythm = editor::tapped_rhythm(taps.sounds(), 0.2, "lra", 3, 5);
            const std::string where =
                "at " + std::to_string(beat) + " s a beat, seed " + std::to_string(seed);
            EXPECT_NEAR(rhythm.tempo, beat, 0.05 * beat) << where;
            const double span = done - onsets.front();
            EXPECT_NEAR(rendered_seconds(rhythm), span, 0.05 * span) << where;
            // Every tapped interval of the same beats is the same length.
            std::map<double, std::set<Length>> written;
            std::size_t k = 0;
            for (const auto& bar : rhythm.bars) {
                for (const auto& symbol : bar.symbols) {
                    ASSERT_TRUE(std::holds_alternative<Note>(symbol)) << where;
                    ASSERT_LT(k, std::size(kTappedBeats)) << where;
                    written[kTappedBeats[k++]].insert(std::get<Note>(symbol).length);
                }
            }
            EXPECT_EQ(k, std::size(kTappedBeats)) << where;
            for (const auto& [beats, lengths] : written) {
                EXPECT_EQ(lengths.size(), 1u) << beats << " beats " << where;
            }
        }
    }
}

// The pair of the issue (355 and 361 ms) tapped in the first bar and again in the second is
// written the same both times.
TEST(TappedRhythm, TheSameTappedPairIsWrittenTheSameInEveryBar) {
    TapRecorder taps;
    double t = 0.0;
    const double gaps[] = {0.4, 0.355, 0.361, 0.4, 0.4, 0.4, 0.4, 0.355, 0.361, 0.4, 0.4};
    for (const double gap : gaps) {
        taps.press_select(at(t));
        t += gap;
    }
    taps.finish(at(t));
    const auto rhythm = editor::tapped_rhythm(taps.sounds(), 0.2, "lra", 3, 5);
    std::vector<Length> lengths;
    for (const auto& bar : rhythm.bars) {
        for (const auto& symbol : bar.symbols) {
            ASSERT_TRUE(std::holds_alternative<Note>(symbol));
            lengths.push_back(std::get<Note>(symbol).length);
        }
    }
    ASSERT_EQ(lengths.size(), std::size(gaps));
    EXPECT_EQ(lengths[1], lengths[7]);
    EXPECT_EQ(lengths[2], lengths[8]);
}

TEST(TappedRhythm, NothingTappedIsNothing) {
    TapRecorder taps;
    taps.finish(at(3.0));
    EXPECT_TRUE(taps.sounds().empty());
    EXPECT_TRUE(editor::tapped_rhythm(taps.sounds(), 0.5, "lra", 3, 5).bars.empty());
}

// The editor's tap entry: the menu's first line, Select taps, Up or Back writes the rhythm.
class TapEntry : public ::testing::Test {
  protected:
    TapEntry() {
        Clef clef;
        clef.tempo = 0.5;
        // A whole clef: a tempo clef made from it is a document the clef reader takes.
        clef.numbers = {0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
        for (int s = 0; s < 6; ++s) {
            clef.strings.push_back({155.0 + 16.0 * s, {}});
        }
        editor.scheme.set_clef_book(editor::ClefBook({{testing::kLra, clef}}));
        testing::to_menu_entry(editor, "tap a rhythm");
        editor.press(editor::Button::select);
    }
    void tap(double down, std::optional<double> up = std::nullopt) {
        editor.press_at(editor::Button::select, at(down));
        if (up) {
            editor.release_at(editor::Button::select, at(*up));
        }
    }
    editor::Editor editor = testing::fresh_editor();
};

TEST_F(TapEntry, TwelveTapsAreFigure75AtTheProposedNoteAndSelectThenChangesThem) {
    ASSERT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::tapping);
    EXPECT_EQ(editor.scheme.hint(editor.model), "tap S:note \u2193rest \u2191 B:done \u2190drop");
    Jitter jitter(3);
    for (int k = 0; k < 12; ++k) {
        tap(jitter(100.0 + 0.8 * k));  // a terminal: presses only
    }
    EXPECT_EQ(editor.scheme.taps(), 12);
    EXPECT_EQ(editor.scheme.hint(editor.model),
              "12 taps S:note \u2193rest \u2191 B:done \u2190drop");
    const auto request = editor.press_at(editor::Button::back, at(jitter(109.6)));
    EXPECT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::browse);
    // Tapped at 0.8 s a beat, not the clef's 0.5: on a copy of the clef at the tapped tempo,
    // declared by the score and stored by the editor (the request).
    auto on_tempo_clef = figure_75();
    for (auto& bar : on_tempo_clef) {
        bar.clef = "lra-75bpm";
    }
    EXPECT_EQ(editor.model.score().bars, on_tempo_clef);
    EXPECT_EQ(editor.model.message(), "12 notes, clef lra-75bpm (0.80 s)");
    EXPECT_EQ(request.kind, editor::Request::Kind::store_clef);
    EXPECT_EQ(request.name, "lra-75bpm");
    EXPECT_DOUBLE_EQ(read_clef(request.document, "lra-75bpm.clef.xml").tempo, 0.8);
    ASSERT_NE(editor.model.score().find_clef("lra-75bpm"), nullptr);
    EXPECT_EQ(editor.model.score().find_clef("lra-75bpm")->href, "lra-75bpm.clef.xml");
    // On the first note tapped, to change them one after another.
    EXPECT_EQ(editor.model.cursor(), (editor::Position{0, 0}));
    // One undo step takes the whole rhythm back.
    ASSERT_TRUE(editor.model.undo());
    EXPECT_TRUE(editor.model.score().bars[0].symbols.empty());
    EXPECT_EQ(editor.model.score().find_clef("lra-75bpm"), nullptr);  // undone with the bars
}

TEST_F(TapEntry, AClefOfTheTempoClefsNameThatIsNotSuchACopyIsLeftAloneAndTheCopyTakesAFreeName) {
    Clef other = editor.scheme.clef_book().find("lra")->clef;
    other.tempo = 0.4;
    other.numbers.back() = 0.9;  // lra-150bpm, but not lra at 0.4 s
    editor.scheme.add_clef({{"lra-150bpm", "lra-150bpm.clef.xml"}, other, false});
    for (int k = 0; k < 4; ++k) {
        tap(1.0 + 0.4 * k);
    }
    const auto request = editor.press_at(editor::Button::back, at(2.6));
    EXPECT_EQ(request.kind, editor::Request::Kind::store_clef);
    EXPECT_EQ(request.name, "lra-150bpm-2");
    EXPECT_EQ(editor.model.message(), "4 notes, clef lra-150bpm-2 (0.40 s)");
    EXPECT_EQ(editor.scheme.clef_book().find("lra-150bpm")->clef, other);
    // Tapped again at that tempo after the tapped bar: that bar's clef plays it already.
    testing::to_menu_entry(editor, "tap a rhythm");
    editor.press(editor::Button::select);
    for (int k = 0; k < 4; ++k) {
        tap(10.0 + 0.4 * k);
    }
    EXPECT_EQ(editor.press_at(editor::Button::back, at(11.6)).kind, editor::Request::Kind::none);
    EXPECT_EQ(editor.model.message(), "4 notes at 0.40 s a beat: S changes");
    for (const auto& bar : editor.model.score().bars) {
        EXPECT_EQ(bar.clef, "lra-150bpm-2");
    }
}

TEST_F(TapEntry, TheTempoClefIsMadeOnceAndFoundAgainAndTapsAtTheClefsPaceNeedNone) {
    EXPECT_EQ(editor.scheme.hint(editor.model), "tap S:note \u2193rest \u2191 B:done \u2190drop");
    tap(1.0);
    EXPECT_EQ(editor.scheme.hint(editor.model), "1 tap S:note \u2193rest \u2191 B:done \u2190drop");
    for (int k = 1; k < 4; ++k) {
        tap(1.0 + 0.4 * k);
    }
    EXPECT_EQ(editor.press_at(editor::Button::back, at(2.6)).kind,
              editor::Request::Kind::store_clef);
    EXPECT_EQ(editor.model.message(), "4 notes, clef lra-150bpm (0.40 s)");
    // Again at that tempo, from the tapped bars: the clef made is found, not made twice.
    testing::to_menu_entry(editor, "tap a rhythm");
    editor.press(editor::Button::select);
    for (int k = 0; k < 4; ++k) {
        tap(10.0 + 0.4 * k);
    }
    EXPECT_EQ(editor.press_at(editor::Button::back, at(11.6)).kind, editor::Request::Kind::none);
    EXPECT_EQ(editor.model.score().bars.size(), 2u);
    for (const auto& bar : editor.model.score().bars) {
        EXPECT_EQ(bar.clef, "lra-150bpm");
    }
}

TEST_F(TapEntry, HeldAndReleasedOnKeysThatSaySoAndUpEndsTapping) {
    tap(10.0, 10.42);
    tap(10.5, 10.92);
    tap(11.0, 11.5);  // let go for a quarter: a rest
    tap(12.0, 12.42);
    editor.press_at(editor::Button::up, at(14.0));
    EXPECT_EQ(editor.model.score().bars,
              testing::bars("<Bar clef=\"lra\"><Note length=\"quarter\" number=\"5\" "
                            "string=\"3\"/><Note length=\"quarter\" number=\"5\" string=\"3\"/>"
                            "<Note length=\"quarter\" number=\"5\" string=\"3\"/>"
                            "<Rest length=\"quarter\"/></Bar><Bar clef=\"lra\">"
                            "<Note length=\"quarter\" number=\"5\" string=\"3\"/></Bar>"));
    EXPECT_EQ(editor.model.message(), "4 notes at 0.50 s a beat: S changes");  // the clef's
}

TEST_F(TapEntry, TappedBarsGoAfterTheBarTheCursorEndsAndLeftDropsTheTaps) {
    editor.press(editor::Button::left);  // dropped: nothing changes
    EXPECT_EQ(editor.model.message(), "tapping dropped");
    EXPECT_TRUE(editor.model.score().bars[0].symbols.empty());
    testing::type(editor, "55");  // a bar with two notes, the cursor at its end
    testing::to_menu_entry(editor, "tap a rhythm");
    editor.press(editor::Button::select);
    tap(1.0);
    tap(1.5);
    editor.press_at(editor::Button::back, at(2.0));
    ASSERT_EQ(editor.model.score().bars.size(), 2u);
    EXPECT_EQ(editor.model.score().bars[0].symbols.size(), 2u);
    EXPECT_EQ(editor.model.score().bars[1].symbols.size(), 2u);
    EXPECT_EQ(editor.model.cursor(), (editor::Position{1, 0}));
}

TEST_F(TapEntry, NothingTappedAndPressesWithoutATimeTapNothing) {
    editor.press(editor::Button::select);  // no time: the press planner's
    editor.press(editor::Button::down);
    EXPECT_EQ(editor.scheme.taps(), 0);
    editor.press(editor::Button::back);
    EXPECT_EQ(editor.model.message(), "nothing tapped");
    EXPECT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::browse);
}

}  // namespace
}  // namespace vibscore
