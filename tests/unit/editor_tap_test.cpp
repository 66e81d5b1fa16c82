// Tapping a rhythm (client/editor/tap_rhythm.*): press and release times with a human's jitter
// in, notes and rests on the score's grid out.
#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "client/editor/tap_rhythm.hpp"
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
    editor.press_at(editor::Button::back, at(jitter(109.6)));
    EXPECT_EQ(editor.scheme.mode(), editor::ButtonScheme::Mode::browse);
    EXPECT_EQ(editor.model.score().bars, figure_75());
    EXPECT_EQ(editor.model.message(), "12 notes at 0.80 s a beat: S changes");
    // On the first note tapped, to change them one after another.
    EXPECT_EQ(editor.model.cursor(), (editor::Position{0, 0}));
    // One undo step takes the whole rhythm back.
    ASSERT_TRUE(editor.model.undo());
    EXPECT_TRUE(editor.model.score().bars[0].symbols.empty());
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
