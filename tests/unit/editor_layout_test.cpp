// The staff layout (thesis Fig. 4.1) that `vibscore show` prints and the editor paints.
#include <gtest/gtest.h>

#include "client/editor/staff_layout.hpp"
#include "client/editor/staff_options.hpp"
#include "client/editor/staff_text.hpp"
#include "tests/support/editor_support.hpp"

namespace vibscore {
namespace {

using editor::Ink;
using editor::layout_staff;
using editor::LayoutOptions;
using editor::Position;
using editor::row_of_string;
using editor::Span;
using editor::StaffLayout;

Score score_of(const std::string& bars_xml) {
    Score score;
    score.clefs = {testing::kLra};
    score.bars = testing::bars(bars_xml);
    return score;
}

std::string row_text(const StaffLayout& layout, int row) {
    return client::staff_row_text(layout, row, 0, layout.width, false);
}

const editor::Cell& cell(const StaffLayout& layout, int row, int x) {
    return layout.rows.at(static_cast<std::size_t>(row)).at(static_cast<std::size_t>(x));
}

TEST(StaffLayout, NoteHeadsCarryTheirNumberOnTheirString) {
    const auto layout = layout_staff(
        score_of("<Bar clef=\"lra\"><Note length=\"quarter\" number=\"7\" string=\"6\"/>"
                 "<Note length=\"quarter\" number=\"2\" string=\"1\"/></Bar>"));
    const int first = layout.x_of({0, 0});
    const int second = layout.x_of({0, 1});
    EXPECT_EQ(cell(layout, row_of_string(6), first).glyph, "7");
    EXPECT_EQ(cell(layout, row_of_string(6), first).ink, Ink::head);
    EXPECT_EQ(cell(layout, row_of_string(1), second).glyph, "2");
    EXPECT_EQ(cell(layout, row_of_string(3), first).glyph, "─");  // the other strings
    EXPECT_EQ(row_of_string(6), editor::row_top_string);
}

TEST(StaffLayout, LongerNotesAreWiderAndDottedOnesShowTheirDot) {
    const auto width_of = [](const char* length) {
        const auto layout = layout_staff(score_of(std::string("<Bar clef=\"lra\"><Note length=\"") +
                                                  length + "\" number=\"1\" string=\"1\"/></Bar>"));
        for (const auto& span : layout.spans) {
            if (span.kind == Span::Kind::symbol) {
                return span.width;
            }
        }
        return 0;
    };
    const char* order[] = {"16th", "8th", "quarter", "half", "whole"};
    for (std::size_t i = 1; i < std::size(order); ++i) {
        EXPECT_LT(width_of(order[i - 1]), width_of(order[i])) << order[i];
    }
    EXPECT_GT(width_of("quarter_dot"), width_of("quarter"));
    const auto dotted = layout_staff(
        score_of("<Bar clef=\"lra\"><Note length=\"8th_dot\" number=\"4\" string=\"2\"/></Bar>"));
    const int x = dotted.x_of({0, 0});
    EXPECT_EQ(cell(dotted, row_of_string(2), x + 1).glyph, "·");
    EXPECT_EQ(cell(dotted, row_of_string(2), x + 2).ink, Ink::sustain);
    EXPECT_EQ(row_text(dotted, editor::row_lengths).substr(static_cast<std::size_t>(x), 2), "8.");
}

TEST(StaffLayout, LengthsAreWrittenUnderTheStaff) {
    const auto layout = layout_staff(
        score_of("<Bar clef=\"lra\"><Note length=\"whole\" number=\"1\" string=\"1\"/>"
                 "<Rest length=\"half_dot\"/><Note length=\"16th\" number=\"1\" string=\"1\"/>"
                 "<Rest length=\"32th\"/></Bar>"));
    const auto lengths = row_text(layout, editor::row_lengths);
    for (std::size_t s = 0; s < 4; ++s) {
        const auto x = static_cast<std::size_t>(layout.x_of({0, s}));
        const std::string expected[] = {"1", "2.", "16", "32"};
        EXPECT_EQ(lengths.substr(x, expected[s].size()), expected[s]) << s;
    }
}

TEST(StaffLayout, RestsSitOnTheMiddleStrings) {
    const auto layout = layout_staff(score_of("<Bar clef=\"lra\"><Rest length=\"8th\"/></Bar>"));
    const int x = layout.x_of({0, 0});
    EXPECT_EQ(cell(layout, row_of_string(4), x).ink, Ink::rest);
    EXPECT_EQ(cell(layout, row_of_string(3), x).ink, Ink::rest);
    EXPECT_EQ(cell(layout, row_of_string(6), x).ink, Ink::line);
}

TEST(StaffLayout, TheClefBoxShowsTheBeatCountColouredFewerExactMore) {
    const auto layout = layout_staff(
        score_of("<Bar clef=\"lra\"><Note length=\"half_dot\" number=\"1\" string=\"1\"/>"
                 "<Note length=\"8th\" number=\"1\" string=\"1\"/></Bar>"
                 "<Bar clef=\"lra\"><Rest length=\"whole\"/></Bar>"
                 "<Bar clef=\"lra\"><Rest length=\"whole\"/><Rest length=\"32th\"/></Bar>"));
    const auto clefs = row_text(layout, editor::row_clef);
    const int bar_x[] = {1, layout.x_of({1, 0}), layout.x_of({2, 0})};
    const std::string boxes[] = {"[lra 3.5]", "[lra 4]", "[lra 4.125]"};
    const Ink inks[] = {Ink::clef_fewer, Ink::clef_exact, Ink::clef_more};
    for (int b = 0; b < 3; ++b) {
        EXPECT_EQ(clefs.substr(static_cast<std::size_t>(bar_x[b]), boxes[b].size()), boxes[b]);
        EXPECT_EQ(cell(layout, editor::row_clef, bar_x[b]).ink, inks[b]) << b;
    }
}

TEST(StaffLayout, TheSymbolStillBeingEnteredIsNotCountedInTheBeats) {
    const Score score = score_of(
        "<Bar clef=\"lra\"><Note length=\"half\" number=\"1\" string=\"1\"/>"
        "<Note length=\"half\" number=\"2\" string=\"1\"/></Bar>");
    editor::LayoutOptions options;
    options.entering = Position{0, 1};
    const auto layout = layout_staff(score, options);
    const auto clefs = row_text(layout, editor::row_clef);
    EXPECT_EQ(clefs.substr(1, 7), "[lra 2]") << clefs;
    EXPECT_EQ(cell(layout, editor::row_clef, 1).ink, Ink::clef_fewer);
    EXPECT_EQ(cell(layout, row_of_string(1), layout.x_of({0, 1})).glyph, "2");  // still drawn
}

TEST(StaffLayout, BarLinesFrameEachBar) {
    const auto layout = layout_staff(
        score_of("<Bar clef=\"lra\"><Rest length=\"quarter\"/></Bar><Bar clef=\"lra\"/>"));
    int lines = 0;
    for (const auto& span : layout.spans) {
        if (span.kind == Span::Kind::bar_line) {
            ++lines;
            for (int s = 1; s <= 6; ++s) {
                EXPECT_EQ(cell(layout, row_of_string(s), span.x).glyph, "│");
            }
        }
    }
    EXPECT_EQ(lines, 3);
    // An empty bar is still as wide as its clef box.
    EXPECT_GE(layout.width, 1 + 8 + 1 + 8 + 1);
}

TEST(StaffLayout, HairpinsSpanTheirRunOfNotes) {
    const auto layout = layout_staff(score_of(
        "<Bar clef=\"lra\"><Note length=\"quarter\" number=\"1\" string=\"1\" "
        "dynamics=\"crescendo\"/>"
        "<Note length=\"quarter\" number=\"5\" string=\"1\" dynamics=\"crescendo\"/>"
        "<Rest length=\"quarter\"/>"
        "<Note length=\"quarter\" number=\"5\" string=\"1\" dynamics=\"decrescendo\"/></Bar>"));
    const auto marks = row_text(layout, editor::row_dynamics);
    const auto first = static_cast<std::size_t>(layout.x_of({0, 0}));
    const auto rest = static_cast<std::size_t>(layout.x_of({0, 2}));
    const auto last = static_cast<std::size_t>(layout.x_of({0, 3}));
    EXPECT_EQ(marks.substr(first, 1), "<");
    EXPECT_EQ(marks.find('>'), marks.size() - 1);
    EXPECT_GT(marks.find('>'), last);
    // The crescendo runs over both notes and stops before the rest.
    EXPECT_EQ(cell(layout, editor::row_dynamics, static_cast<int>(rest) - 2).glyph, "─");
    EXPECT_EQ(cell(layout, editor::row_dynamics, static_cast<int>(rest)).glyph, " ");
}

TEST(StaffLayout, LegatoAndPortamentoMarksJoinTheTiedHeads) {
    const auto layout = layout_staff(
        score_of("<Bar clef=\"lra\"><Note length=\"8th\" number=\"1\" string=\"1\" legato=\"1\"/>"
                 "<Note length=\"8th\" number=\"1\" string=\"2\" legato=\"1\"/>"
                 "<Note length=\"8th\" number=\"1\" string=\"3\" legato=\"1\" portamento=\"1\"/>"
                 "<Note length=\"8th\" number=\"1\" string=\"4\" portamento=\"1\"/></Bar>"));
    const auto x = [&](std::size_t s) { return layout.x_of({0, s}); };
    EXPECT_EQ(cell(layout, editor::row_ties, x(0)).glyph, "╰");
    EXPECT_EQ(cell(layout, editor::row_ties, x(1)).glyph, "┴");
    EXPECT_EQ(cell(layout, editor::row_ties, x(3)).glyph, "~");
    EXPECT_EQ(cell(layout, editor::row_ties, x(2) + 1).glyph, "~");
}

TEST(StaffLayout, TheEditorsCursorBlockAndPlaybackCursor) {
    const auto score = score_of(
        "<Bar clef=\"lra\"><Note length=\"quarter\" number=\"1\" string=\"2\"/>"
        "<Note length=\"quarter\" number=\"1\" string=\"2\"/></Bar>");
    LayoutOptions options;
    options.end_positions = true;
    options.cursor = Position{0, 2};  // the empty position at the end of the bar
    options.cursor_string = 5;
    options.block = editor::Block{{0, 0}, {0, 1}};
    options.playing = Position{0, 1};
    const auto layout = layout_staff(score, options);
    const int end = layout.x_of({0, 2});
    ASSERT_GT(end, layout.x_of({0, 1}));
    EXPECT_TRUE(cell(layout, row_of_string(5), end).overlay & editor::overlay_cursor);
    EXPECT_TRUE(cell(layout, row_of_string(1), end).overlay & editor::overlay_cursor_column);
    EXPECT_FALSE(cell(layout, row_of_string(1), end).overlay & editor::overlay_cursor);
    EXPECT_TRUE(cell(layout, row_of_string(2), layout.x_of({0, 0})).overlay &
                editor::overlay_selected);
    EXPECT_FALSE(cell(layout, row_of_string(2), layout.x_of({0, 1})).overlay &
                 editor::overlay_selected);
    EXPECT_EQ(cell(layout, editor::row_playback, layout.x_of({0, 1})).glyph, "●");
    // Without end positions (show) the end of a bar has no place of its own.
    EXPECT_EQ(layout_staff(score).x_of({0, 2}), -1);
}

TEST(StaffLayout, TheCursorAndTheBlockAreMarkedWithGlyphsNotOnlyColour) {
    // Colour alone is lost on a monochrome terminal and in a capture of the screen.
    const auto score = score_of(
        "<Bar clef=\"lra\"><Note length=\"quarter\" number=\"1\" string=\"2\"/>"
        "<Rest length=\"8th\"/><Note length=\"quarter\" number=\"3\" string=\"2\"/></Bar>");
    LayoutOptions options;
    options.end_positions = true;
    options.cursor = Position{0, 2};
    options.block = editor::Block{{0, 0}, {0, 2}};
    const auto layout = layout_staff(score, options);
    const std::string marks = row_text(layout, editor::row_playback);
    const int cursor_x = layout.x_of({0, 2});
    EXPECT_EQ(cell(layout, editor::row_playback, cursor_x).glyph, "▲") << marks;
    for (int x = layout.x_of({0, 0}); x < layout.x_of({0, 2}); ++x) {
        EXPECT_EQ(cell(layout, editor::row_playback, x).glyph, "═") << marks;
    }
    EXPECT_EQ(cell(layout, editor::row_playback, cursor_x + 1).glyph, " ") << marks;
    // show draws neither.
    EXPECT_EQ(row_text(layout_staff(score), editor::row_playback).find_first_not_of(' '),
              std::string::npos);
}

TEST(StaffLayout, TheCursorsLabelSaysWhatTheOpenSymbolIsEvenAtTheEndOfTheStaff) {
    const auto score = score_of(
        "<Bar clef=\"lra\"><Note length=\"16th\" number=\"1\" "
        "string=\"2\"/></Bar>");
    LayoutOptions options;
    options.end_positions = true;
    options.cursor = Position{0, 0};
    options.cursor_label = "change";
    const auto layout = layout_staff(score, options);
    const std::string marks = row_text(layout, editor::row_playback);
    EXPECT_NE(marks.find("▲change"), std::string::npos) << marks;
    // The staff lines stop at the last bar line; the label may reach past it.
    options.cursor = Position{0, 1};
    const auto at_end = layout_staff(score, options);
    EXPECT_NE(row_text(at_end, editor::row_playback).find("▲change"), std::string::npos);
    const std::string line = row_text(at_end, row_of_string(1));
    EXPECT_TRUE(line.ends_with("│ ") || line.ends_with("│")) << line;
}

TEST(StaffLayout, SystemsBreakAtBarLinesAndRepeatThem) {
    Score score = score_of("");
    for (int b = 0; b < 6; ++b) {
        score.bars.push_back(
            testing::bars("<Bar clef=\"lra\"><Note length=\"quarter\" number=\"1\" "
                          "string=\"1\"/><Note length=\"half\" number=\"2\" "
                          "string=\"2\"/></Bar>")[0]);
    }
    const auto layout = layout_staff(score);
    const auto ranges = editor::systems(layout, 30);
    ASSERT_GT(ranges.size(), 1u);
    EXPECT_EQ(ranges.front().first, 0);
    EXPECT_EQ(ranges.back().second, layout.width);
    for (std::size_t i = 0; i < ranges.size(); ++i) {
        EXPECT_LE(ranges[i].second - ranges[i].first, 30);
        EXPECT_EQ(cell(layout, row_of_string(1), ranges[i].first).glyph, "│");
        EXPECT_EQ(cell(layout, row_of_string(1), ranges[i].second - 1).glyph, "│");
        if (i > 0) {
            EXPECT_EQ(ranges[i].first, ranges[i - 1].second - 1);
        }
    }
}

TEST(StaffLayout, ScrollingKeepsTheCursorInsideWithAMargin) {
    EXPECT_EQ(editor::scroll_to_show(0, 40, 10, 200), 0);
    const int moved = editor::scroll_to_show(0, 40, 50, 200);
    EXPECT_GT(50, moved + 6);
    EXPECT_LT(50, moved + 40 - 6 + 1);
    EXPECT_EQ(editor::scroll_to_show(100, 40, 102, 200), 96);
    EXPECT_EQ(editor::scroll_to_show(0, 40, 199, 200), 160);
    EXPECT_EQ(editor::scroll_to_show(50, 40, 0, 30), 0);
}

TEST(StaffText, PlainTextHasNoEscapesAndColourTextColoursTheClefBox) {
    const auto layout = layout_staff(
        score_of("<Bar clef=\"lra\"><Note length=\"whole\" number=\"1\" string=\"1\"/></Bar>"));
    const auto plain = client::staff_row_text(layout, editor::row_clef, 0, layout.width, false);
    EXPECT_EQ(plain.find('\x1b'), std::string::npos);
    EXPECT_EQ(plain, " [lra 4]");
    const auto colour = client::staff_row_text(layout, editor::row_clef, 0, layout.width, true);
    EXPECT_NE(colour.find("\x1b[30;47m[lra 4]"), std::string::npos) << colour;
}

TEST(StaffText, BeatLabels) {
    EXPECT_EQ(editor::beat_label(4.0), "4");
    EXPECT_EQ(editor::beat_label(3.5), "3.5");
    EXPECT_EQ(editor::beat_label(0.375), "0.375");
    EXPECT_EQ(editor::beat_label(0.0), "0");
}

// The bar box of the bar being entered, "[clef beats]".
std::string bar_box(const editor::Editor& editor) {
    const auto options = editor::staff_options(editor.model, editor.scheme, std::nullopt);
    const auto clefs = row_text(layout_staff(editor.model.score(), options), editor::row_clef);
    return clefs.substr(clefs.find('['), clefs.find(']') - clefs.find('[') + 1);
}

TEST(StaffLayout, ABarBoxCountsTheSymbolBeingChangedButNotAProposal) {
    // Changing the first of three quarters, the box read 2 beats: the note was still there.
    auto editor = testing::fresh_editor();
    testing::type(editor, "555");
    const std::string clef = editor.model.score().bars[0].clef;
    ASSERT_EQ(bar_box(editor), "[" + clef + " 3]");
    testing::press(editor, {testing::buttons::L, testing::buttons::L, testing::buttons::L,
                            testing::buttons::S});
    ASSERT_TRUE(editor.model.changing());
    EXPECT_EQ(bar_box(editor), "[" + clef + " 3]");
    // A proposal at the end of the bar is not the bar's until it is entered.
    auto proposing = testing::fresh_editor();
    testing::type(proposing, "555");
    testing::press(proposing, {testing::buttons::S});
    ASSERT_EQ(proposing.scheme.mode(), editor::ButtonScheme::Mode::entry);
    ASSERT_FALSE(proposing.model.changing());
    EXPECT_EQ(bar_box(proposing), "[" + clef + " 3]");
}

}  // namespace
}  // namespace vibscore
