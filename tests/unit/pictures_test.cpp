// The staff and signal pictures: SVG that parses with one note head per note (as cairo 1.16 and
// 1.18 each write it), PNG of the expected size with ink where the notes are, no two kinds of
// ink in one place that should be apart, and thesis Fig. 2.3a's first measure and the README's
// pictures against committed golden images, compared by what they show on any cairo version;
// the picture of what a declared actuator makes of a score (render --actuator) likewise.
#include <gtest/gtest.h>
#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "actuator/physics.hpp"
#include "client/formats/rtttl.hpp"
#include "client/pictures/clef_picture.hpp"
#include "client/pictures/response_picture.hpp"
#include "client/pictures/signal_picture.hpp"
#include "client/pictures/staff_picture.hpp"
#include "daemon/config.hpp"
#include "daemon/render/actuator_response.hpp"
#include "daemon/render/waveform.hpp"
#include "score/bundle.hpp"
#include "tests/support/example_actuators.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"
#include "tests/unit/picture_ink.hpp"

namespace vibscore {
namespace {

using vibscore::testing::example_erm;
using vibscore::testing::example_lra;

using pictures::Layers;
using pictures::ResponsePicture;
using pictures::SignalPicture;
using pictures::StaffPicture;
using testing::Image;
using testing::TempDir;

std::filesystem::path shipped(const std::string& name) {
    return std::filesystem::path(testing::required_env("VIBSCORE_CLEFS")) / name;
}

std::filesystem::path golden(const std::string& name) {
    return std::filesystem::path(testing::required_env("VIBSCORE_GOLDEN")) / name;
}

Score shipped_score(const std::string& name) {
    return read_score(read_document_file(shipped(name)), name).score;
}

// Für Elise as `vibscore convert` imports it onto lra-phone: eighth notes on string 6 with
// flags, and a waveform at full scale.
ScoreBundle fur_elise() {
    const auto file = shipped("..") / "examples" / "rtttl" / "fur-elise.rtttl";
    const formats::ChosenClef chosen{"lra-phone", load_clef_file(shipped("lra-phone.clef.xml"))};
    auto imported = formats::read_rtttl(read_document_file(file), file.string(), chosen);
    ScoreBundle bundle;
    bundle.file = file.string();
    bundle.score = std::move(imported.score);
    for (auto& clef : imported.clefs) {
        bundle.clefs.emplace(clef.id, std::move(clef.clef));
    }
    return bundle;
}

std::size_t count_notes(const Score& score) {
    return testing::notes_in(score).size();
}

// cairo 1.16 writes a path's colours in its style ("stroke:rgb(8%,8%,25%);"), 1.18 as
// attributes (stroke="rgb(8%, 8%, 25%)"): the stroke colour either way, without blanks.
std::string stroke_of(const pugi::xml_node& path) {
    std::string stroke = path.attribute("stroke").value();
    const std::string style = path.attribute("style").value();
    if (const auto at = style.find("stroke:"); at != std::string::npos) {
        stroke = style.substr(at + 7, style.find(';', at) - at - 7);
    }
    stroke.erase(std::remove(stroke.begin(), stroke.end(), ' '), stroke.end());
    return stroke;
}

std::string head_stroke() {
    char text[64];
    std::snprintf(text, sizeof text, "rgb(%g%%,%g%%,%g%%)", StaffPicture::head_ink[0] * 100,
                  StaffPicture::head_ink[1] * 100, StaffPicture::head_ink[2] * 100);
    return text;
}

TEST(StaffPicture, TheSvgParsesAndHoldsOneNoteHeadPerNote) {
    TempDir dir;
    for (const char* name :
         {"ode-to-joy.score.xml", "ringtone.score.xml", "delete-file.score.xml"}) {
        SCOPED_TRACE(name);
        const auto score = shipped_score(name);
        const StaffPicture picture(score);
        const auto svg = dir.path() / "staff.svg";
        pictures::write_picture(picture, svg);
        pugi::xml_document document;
        ASSERT_TRUE(document.load_file(svg.c_str())) << testing::read_file(svg);
        ASSERT_STREQ(document.document_element().name(), "svg");
        std::size_t heads = 0;
        for (const auto& path : document.select_nodes("//path")) {
            heads += stroke_of(path.node()) == head_stroke() ? 1 : 0;
        }
        EXPECT_EQ(heads, count_notes(score));
        EXPECT_EQ(picture.head_centres().size(), count_notes(score));
    }
}

TEST(StaffPicture, ThePngHasItsSizeAndInkAtEveryNoteHead) {
    TempDir dir;
    const auto score = shipped_score("ode-to-joy.score.xml");
    const StaffPicture picture(score);
    const auto png = dir.path() / "staff.png";
    pictures::write_picture(picture, png);
    const auto image = Image::read_png(png);
    EXPECT_EQ(image.width(), static_cast<int>(picture.width()));
    EXPECT_EQ(image.height(), static_cast<int>(picture.height()));
    // A long score breaks into systems, so the picture is taller than one staff.
    EXPECT_GT(picture.height(), 2 * 150.0);
    for (const auto& head : picture.head_centres()) {
        // The head's outline at its left edge is ink whatever the head's fill.
        EXPECT_FALSE(image.at(static_cast<int>(head.x - 7), static_cast<int>(head.y)).white())
            << head.x << "," << head.y;
    }
    EXPECT_TRUE(image.at(2, image.height() - 2).white());
}

TEST(StaffPicture, TheClefBoxOfABarStartingTheNextSystemIsDrawnThereOnly) {
    const auto score = shipped_score("ode-to-joy.score.xml");
    const StaffPicture picture(score);
    const auto image = Image::of(picture);
    // Every system ends at its closing bar line, inside the right margin: the margin's last
    // columns hold no ink, not the start of a box for the bar that opens the next system.
    for (int y = 0; y < image.height(); ++y) {
        for (int x = image.width() - 6; x < image.width(); ++x) {
            ASSERT_TRUE(image.at(x, y).white()) << x << "," << y;
        }
    }
    EXPECT_EQ(picture.clef_boxes_drawn().size(), score.bars.size());
}

// --- No two kinds of ink in one place ------------------------------------------------------

struct NamedLayer {
    Layers layer;
    const char* name;
};

// Each pair of `layers` shares no pixel that both hold a sixteenth of ink in, except the pairs in
// `may_meet`, which touch or cross by design (a stem rises from its head, a bar line crosses
// the strings).
// Returns the layers that hold ink.
Layers expect_apart(const pictures::Drawing& picture, const std::vector<NamedLayer>& layers,
                    const std::set<std::pair<Layers, Layers>>& may_meet) {
    std::vector<Image> inks;
    Layers inked = 0;
    for (const auto& layer : layers) {
        inks.push_back(Image::ink_of(picture, layer.layer));
        inked |= testing::shared_ink(inks.back(), inks.back()).empty() ? 0 : layer.layer;
    }
    for (std::size_t i = 0; i < layers.size(); ++i) {
        for (std::size_t j = i + 1; j < layers.size(); ++j) {
            if (may_meet.contains({layers[i].layer, layers[j].layer}) ||
                may_meet.contains({layers[j].layer, layers[i].layer})) {
                continue;
            }
            const auto shared = testing::shared_ink(inks[i], inks[j]);
            EXPECT_TRUE(shared.empty())
                << layers[i].name << " and " << layers[j].name << " share " << shared.size()
                << " pixels, the first at (" << (shared.empty() ? 0 : shared[0].x) << ","
                << (shared.empty() ? 0 : shared[0].y) << ")";
        }
    }
    return inked;
}

// Every layer drew something in one of the pictures checked, or the check proved nothing.
void expect_every_layer_checked(Layers inked, const std::vector<NamedLayer>& layers) {
    for (const auto& layer : layers) {
        EXPECT_TRUE(inked & layer.layer) << layer.name << " drew nothing to check";
    }
}

const std::vector<NamedLayer> kStaffLayers{
    {StaffPicture::title, "the title"},
    {StaffPicture::staff_lines, "the strings"},
    {StaffPicture::bar_lines, "the bar lines"},
    {StaffPicture::clef_boxes, "the clef boxes"},
    {StaffPicture::clef_labels, "the clef labels"},
    {StaffPicture::heads, "the note heads"},
    {StaffPicture::numbers, "the numbers"},
    {StaffPicture::stems, "the stems and flags"},
    {StaffPicture::rests, "the rests"},
    {StaffPicture::hairpins, "the hairpins"},
    {StaffPicture::ties, "the ties"},
};

const std::set<std::pair<Layers, Layers>> kStaffMayMeet{
    {StaffPicture::staff_lines, StaffPicture::bar_lines},
    {StaffPicture::staff_lines, StaffPicture::heads},
    {StaffPicture::staff_lines, StaffPicture::numbers},
    {StaffPicture::staff_lines, StaffPicture::stems},
    {StaffPicture::staff_lines, StaffPicture::rests},
    {StaffPicture::staff_lines, StaffPicture::ties},
    {StaffPicture::clef_boxes, StaffPicture::clef_labels},
    {StaffPicture::heads, StaffPicture::numbers},
    {StaffPicture::heads, StaffPicture::stems},
    {StaffPicture::heads, StaffPicture::ties},
};

// Notes on string 6 with flags under a hairpin, every length, rests, dots, legato and
// portamento, on a clef with a long name and in bars of every beat count.
Score crowded_score() {
    const auto clef = testing::sine_clef(0.5, {100, 120, 140, 160, 180, 200}, {0.2, 0.5, 1.0});
    const std::string xml = R"(<?xml version="1.0"?>
<VibScore version="1.0"><Title>Crowded</Title>
<Clef id="a-clef-with-a-long-name" href="c.xml"/>
<Clef id="c" href="c.xml"/>
<Clef id="WWWWWWWWWWWWWWWWWWWW" href="c.xml"/>
<Bar clef="a-clef-with-a-long-name">
  <Note length="32th" number="3" string="6" dynamics="crescendo"/>
  <Note length="16th" number="2" string="6" dynamics="crescendo"/>
  <Note length="8th_dot" number="1" string="6" dynamics="crescendo"/>
  <Note length="quarter" number="3" string="1" legato="1"/>
  <Note length="8th" number="3" string="6" legato="1"/>
  <Rest length="16th"/>
  <Note length="16th" number="2" string="6" portamento="1"/>
  <Note length="16th" number="2" string="1" portamento="1"/>
</Bar>
<Bar clef="WWWWWWWWWWWWWWWWWWWW"><Note length="32th" number="1" string="6"/></Bar>
<Bar clef="c">
  <Note length="16th" number="1" string="5"/><Note length="16th" number="2" string="6"/>
  <Note length="16th" number="3" string="4"/><Note length="16th" number="1" string="6"/>
</Bar>
<Bar clef="c">
  <Note length="half" number="3" string="6" dynamics="decrescendo"/>
  <Note length="8th" number="3" string="6" dynamics="decrescendo"/>
  <Rest length="quarter"/><Rest length="8th_dot"/><Rest length="half"/>
</Bar>
<Bar clef="c"><Note length="whole" number="2" string="6"/><Rest length="whole"/></Bar>
</VibScore>)";
    return testing::bundle_from(xml, {{"c.xml", clef}}).score;
}

TEST(StaffPicture, KeepsStemsOutOfClefBoxesAndHairpinsAndEveryMarkApart) {
    const auto ode = shipped_score("ode-to-joy.score.xml");
    const auto elise = fur_elise().score;
    const auto crowded = crowded_score();
    Layers inked = 0;
    for (const auto* score : {&ode, &elise, &crowded}) {
        SCOPED_TRACE(score->title);
        inked |= expect_apart(StaffPicture(*score), kStaffLayers, kStaffMayMeet);
    }
    expect_every_layer_checked(inked, kStaffLayers);
}

TEST(StaffPicture, FindsTheStemThatRanThroughAClefBox) {
    // The check itself: a stem drawn where a clef box is, as pictures were drawn before, is
    // found.
    const auto score = fur_elise().score;
    const StaffPicture picture(score);
    const auto boxes = Image::ink_of(picture, StaffPicture::clef_boxes);
    auto stems = Image::ink_of(picture, StaffPicture::stems);
    const auto& box = picture.clef_boxes_drawn().front();
    for (int y = static_cast<int>(box.y); y < static_cast<int>(box.y + 40); ++y) {
        stems.set(static_cast<int>(box.x + 12), y, {0, 0, 0, 255});
    }
    EXPECT_FALSE(testing::shared_ink(boxes, stems).empty());
}

TEST(StaffPicture, TheClefBoxSaysItsNumberIsTheBeatCount) {
    const auto ode = shipped_score("ode-to-joy.score.xml");
    const StaffPicture ode_picture(ode);
    for (const auto& box : ode_picture.clef_boxes_drawn()) {
        EXPECT_EQ(box.label, "shaker  4 beats");
    }
    const auto crowded = crowded_score();
    const StaffPicture crowded_picture(crowded);
    const auto& boxes = crowded_picture.clef_boxes_drawn();
    ASSERT_EQ(boxes.size(), 5u);
    EXPECT_EQ(boxes[0].label, "a-clef-with-a-long-name  3.375 beats");
    // A bar of one 32nd note is too narrow for "beats" after a wide name: the count alone.
    EXPECT_EQ(boxes[1].label, "WWWWWWWWWWWWWWWWWWWW  0.125");
    EXPECT_EQ(boxes[2].label, "c  1 beat");
    EXPECT_EQ(boxes[3].label, "c  6.25 beats");
    EXPECT_EQ(boxes[4].label, "c  8 beats");
    // Each box ends before the next in its system begins.
    for (std::size_t b = 0; b + 1 < boxes.size(); ++b) {
        if (boxes[b].y == boxes[b + 1].y) {
            EXPECT_LT(boxes[b].x + boxes[b].width, boxes[b + 1].x) << "box " << b;
        }
    }
}

// --- Golden pictures -----------------------------------------------------------------------

// thesis Fig. 2.3a's first measure, drawn in-process.
struct Figure23a {
    Score score = read_score(read_document_file(golden("figure-2-3a.score.xml")), "fig").score;
    StaffPicture picture{score};
};

std::string differences(const std::filesystem::path& committed, const Image& drawn,
                        const testing::GoldenCheck& check) {
    return check.differences(Image::read_png(committed), drawn);
}

TEST(StaffPicture, Figure23aFirstMeasureShowsWhatTheGoldenImageShows) {
    TempDir dir;
    const auto drawn = dir.path() / "figure.png";
    const auto result =
        testing::run_command({testing::required_env("VIBSCORE"), "show",
                              golden("figure-2-3a.score.xml").string(), "--png", drawn.string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const Figure23a figure;
    EXPECT_EQ(differences(golden("figure-2-3a-staff.png"), Image::read_png(drawn),
                          testing::GoldenCheck(figure.picture)),
              "");
}

// A documented picture command, as README.md and docs/*.md write it:
// "build/client/vibscore show clefs/x.score.xml --png docs/pictures/x.png".
struct PictureCommand {
    std::string line;
    std::vector<std::string> words;  // after "vibscore"
    std::string document, picture;   // the document drawn, and the picture written
    std::string actuator;            // render/show --actuator FILE: the file declaring it
};

std::vector<PictureCommand> documented_picture_commands(const std::filesystem::path& root) {
    std::vector<PictureCommand> commands;
    for (const char* file : {"README.md", "docs/formats.md", "docs/clefs.md"}) {
        std::istringstream text(testing::read_file(root / file));
        for (std::string line; std::getline(text, line);) {
            const auto at = line.find("build/client/vibscore ");
            if (at == std::string::npos || line.find("--png docs/pictures/") == std::string::npos) {
                continue;
            }
            PictureCommand command{line, {}, {}, {}, {}};
            std::istringstream words(
                line.substr(at + std::string("build/client/vibscore ").size()));
            for (std::string word; words >> word && word != "#";) {
                command.words.push_back(word);
            }
            for (std::size_t w = 1; w < command.words.size(); ++w) {
                if (command.words[w] == "--png" && w + 1 < command.words.size()) {
                    command.picture = command.words[++w];
                } else if (command.words[w] == "--actuator" && w + 1 < command.words.size()) {
                    command.actuator = command.words[++w];
                } else if (command.words[w].starts_with("--")) {
                    ++w;  // an option's value
                } else if (command.document.empty()) {
                    command.document = command.words[w];
                }
            }
            commands.push_back(command);
        }
    }
    return commands;
}

// The picture a command draws, drawn in-process, for the golden check's text layers.
struct InProcess {
    std::optional<Score> score;
    std::optional<Clef> clef;
    std::optional<ScoreBundle> bundle;
    std::optional<render::Performance> performance;
    std::unique_ptr<pictures::Drawing> picture;
};

// What `render --actuator` draws, as its client does: the declaration's brake says whether the
// board can drive backwards, and the response is sampled at 1 kHz.
// The clefs line of the caption and the bar labels, as `render --actuator FILE` gives them:
// the clefs as written, by registry name.
std::pair<std::string, ResponsePicture::Options> written_clefs(const ScoreBundle& bundle) {
    const auto name = [](const ClefDeclaration& clef) {
        return clef.href.substr(0, clef.href.find(".clef.xml"));
    };
    std::pair<std::string, ResponsePicture::Options> result{"clefs as written: ", {}};
    for (const auto& clef : bundle.score.clefs) {
        result.first += (&clef == &bundle.score.clefs.front() ? "" : ", ") + name(clef);
    }
    for (const auto& bar : bundle.score.bars) {
        for (const auto& clef : bundle.score.clefs) {
            if (clef.id == bar.clef) {
                result.second.bar_clefs.push_back(name(clef));
            }
        }
    }
    return result;
}

// The caption's clef line and the bar labels as the client gives them (`clefs`: its line).
std::unique_ptr<ResponsePicture> response_picture(const render::Performance& performance,
                                                  const actuator::Declaration& declared,
                                                  const std::string& title,
                                                  const std::string& clefs = "",
                                                  const ResponsePicture::Options& picture = {}) {
    render::ResponseOptions options;
    options.rate_hz = 1000.0;
    options.reverse = declared.brake == actuator::Brake::reverse;
    return std::make_unique<ResponsePicture>(
        performance, render::actuator_response(performance, declared, options), title,
        "on the actuator: " + actuator::describe(declared) + (clefs.empty() ? "" : "\n" + clefs),
        picture);
}

std::unique_ptr<InProcess> draw_in_process(const std::string& verb,
                                           const std::filesystem::path& document,
                                           const std::filesystem::path& actuator_file = {}) {
    auto drawn = std::make_unique<InProcess>();
    const auto text = read_document_file(document);
    if (verb == "render" && !actuator_file.empty()) {
        drawn->bundle = load_score_file(document);
        drawn->performance.emplace(*drawn->bundle);
        const auto declared = daemon::load_config(actuator_file).actuator;
        EXPECT_TRUE(declared) << actuator_file << " declares no actuator";
        const auto [clefs, options] = written_clefs(*drawn->bundle);
        drawn->picture =
            response_picture(*drawn->performance, declared.value_or(actuator::Declaration{}),
                             drawn->bundle->score.title, clefs, options);
    } else if (verb == "render") {
        drawn->bundle = load_score_file(document);
        drawn->performance.emplace(*drawn->bundle);
        drawn->picture =
            std::make_unique<SignalPicture>(*drawn->performance, drawn->bundle->score.title);
    } else if (document_kind(text, document.string()) == DocumentKind::clef) {
        drawn->clef = read_clef(text, document.string());
        std::optional<actuator::Declaration> declared;
        if (!actuator_file.empty()) {
            declared = daemon::load_config(actuator_file).actuator;
            EXPECT_TRUE(declared) << actuator_file << " declares no actuator";
        }
        drawn->picture = std::make_unique<pictures::ClefPicture>(
            *drawn->clef, document.filename().string(), declared);
    } else {
        drawn->score = read_score(text, document.string()).score;
        drawn->picture = std::make_unique<StaffPicture>(*drawn->score);
    }
    return drawn;
}

// The README and docs show pictures; the commands beside them must still draw them.
TEST(Pictures, EveryPictureInTheDocsIsWhatItsCommandDraws) {
    TempDir dir;
    const auto root = shipped("..");
    const auto commands = documented_picture_commands(root);
    // The README's staff and signal, the docs' clef, a tacton on the feel issue's ERM, and
    // lra-phone on its LRA before and after fitting.
    ASSERT_GE(commands.size(), 6u);
    for (const auto& command : commands) {
        SCOPED_TRACE(command.line);
        std::vector<std::string> argv{testing::required_env("VIBSCORE")};
        for (const auto& word : command.words) {
            // Paths are the checkout's; the picture is drawn afresh, not over the committed one.
            argv.push_back(word == command.picture ? (dir.path() / "drawn.png").string()
                           : std::filesystem::exists(root / word) ? (root / word).string()
                                                                  : word);
        }
        const auto result = testing::run_command(argv);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        const auto in_process = draw_in_process(
            command.words.at(0), root / command.document,
            command.actuator.empty() ? std::filesystem::path() : root / command.actuator);
        EXPECT_EQ(differences(root / command.picture, Image::read_png(dir.path() / "drawn.png"),
                              testing::GoldenCheck(*in_process->picture)),
                  "");
    }
}

// --- The golden comparison fails when something moves or vanishes ---------------------------

struct Window {
    int x0, y0, x1, y1;  // inclusive
};

// `image` with the content of `window` moved by (dx, dy) pixels, what moves in taken from
// around it.
Image moved(const Image& image, Window window, int dx, int dy) {
    Image result = image;
    for (int y = window.y0; y <= window.y1; ++y) {
        for (int x = window.x0; x <= window.x1; ++x) {
            result.set(x, y, image.at(x - dx, y - dy));
        }
    }
    return result;
}

// `image` with `window` taken from `other`.
Image patched(const Image& image, const Image& other, Window window) {
    Image result = image;
    for (int y = window.y0; y <= window.y1; ++y) {
        for (int x = window.x0; x <= window.x1; ++x) {
            result.set(x, y, other.at(x, y));
        }
    }
    return result;
}

Window around(const StaffPicture::Point& head, int rx, int ry) {
    const int x = static_cast<int>(head.x), y = static_cast<int>(head.y);
    return {x - rx, y - ry, x + rx, y + ry};
}

// The first and last columns that hold a layer's ink.
std::pair<int, int> inked_columns(const Image& ink) {
    int first = ink.width(), last = -1;
    for (int y = 0; y < ink.height(); ++y) {
        for (int x = 0; x < ink.width(); ++x) {
            if (ink.at(x, y).a > 128) {
                first = std::min(first, x);
                last = std::max(last, x);
            }
        }
    }
    return {first, last};
}

TEST(GoldenComparison, FailsWhenAHeadStemOrLineMovesOnePixelOrVanishes) {
    const Figure23a figure;
    const auto& picture = figure.picture;
    const auto golden_png = golden("figure-2-3a-staff.png");
    const auto drawn = Image::of(picture);
    const testing::GoldenCheck check(picture);
    ASSERT_EQ(differences(golden_png, drawn, check), "");
    const auto heads = picture.head_centres();
    ASSERT_EQ(heads.size(), 3u);
    const auto without = [&](Layers layers) {
        return Image::of(picture, pictures::all_layers & ~layers);
    };
    for (const auto& head : heads) {
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            EXPECT_NE(differences(golden_png, moved(drawn, around(head, 10, 8), dx, dy), check), "")
                << "head at " << head.x << " moved by " << dx << "," << dy;
        }
        EXPECT_NE(
            differences(golden_png,
                        patched(drawn, without(StaffPicture::heads), around(head, 9, 7)), check),
            "")
            << "head at " << head.x << " gone";
        // The stem over the head, above the head.
        const Window stem{static_cast<int>(head.x) + 4, static_cast<int>(head.y) - 40,
                          static_cast<int>(head.x) + 9, static_cast<int>(head.y) - 8};
        EXPECT_NE(
            differences(golden_png, patched(drawn, without(StaffPicture::stems), stem), check), "")
            << "stem of the head at " << head.x << " gone";
        EXPECT_NE(differences(golden_png, moved(drawn, stem, 1, 0), check), "")
            << "stem of the head at " << head.x << " moved";
    }
    // The string under the first head, a stretch of it one pixel lower or higher.
    const int string_y = static_cast<int>(heads[0].y);
    for (const int dy : {1, -1}) {
        EXPECT_NE(differences(golden_png,
                              moved(drawn, {60, string_y - 3, 120, string_y + 3}, 0, dy), check),
                  "");
    }
    // The closing bar line, a pixel to either side, or gone.
    const auto [first_bar_line, last_bar_line] =
        inked_columns(Image::ink_of(picture, StaffPicture::bar_lines));
    const Window closing{last_bar_line - 3, 0, last_bar_line + 3, drawn.height() - 1};
    EXPECT_NE(differences(golden_png, moved(drawn, closing, 1, 0), check), "");
    EXPECT_NE(differences(golden_png, moved(drawn, closing, -1, 0), check), "");
    EXPECT_NE(
        differences(golden_png, patched(drawn, without(StaffPicture::bar_lines), closing), check),
        "");
    EXPECT_LT(first_bar_line, last_bar_line);
}

TEST(GoldenComparison, FailsWhenANumberChangesMovesOrVanishes) {
    const Figure23a figure;
    const auto& picture = figure.picture;
    const auto golden_png = golden("figure-2-3a-staff.png");
    const auto drawn = Image::of(picture);
    const testing::GoldenCheck check(picture);
    const auto heads = picture.head_centres();
    for (std::size_t h = 0; h < heads.size(); ++h) {
        const auto window = around(heads[h], 5, 5);
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            EXPECT_NE(differences(golden_png, moved(drawn, window, dx, dy), check), "")
                << "number " << h << " moved by " << dx << "," << dy;
        }
        EXPECT_NE(
            differences(
                golden_png,
                patched(drawn, Image::of(picture, pictures::all_layers & ~StaffPicture::numbers),
                        window),
                check),
            "")
            << "number " << h << " gone";
        // Every other number in its place.
        for (int number = 1; number <= 9; ++number) {
            Score changed = figure.score;
            std::size_t seen = 0;
            int was = 0;
            for (auto& symbol : changed.bars[0].symbols) {
                if (auto* note = std::get_if<Note>(&symbol); note && seen++ == h) {
                    was = note->number;
                    note->number = number;
                }
            }
            if (number == was) {
                continue;
            }
            const StaffPicture other(changed);
            EXPECT_NE(differences(golden_png, patched(drawn, Image::of(other), window), check), "")
                << "number " << h << " written " << number << " instead of " << was;
        }
    }
}

TEST(GoldenComparison, FailsWhenALabelChangesOrMovesButNotWhenTextIsALittleLighter) {
    const Figure23a figure;
    const auto& picture = figure.picture;
    const auto golden_png = golden("figure-2-3a-staff.png");
    const auto drawn = Image::of(picture);
    const testing::GoldenCheck check(picture);
    const auto& box = picture.clef_boxes_drawn().at(0);
    EXPECT_EQ(box.label, "fig23  4 beats");
    const Window label{static_cast<int>(box.x) + 2, static_cast<int>(box.y) + 2,
                       static_cast<int>(box.x + box.width) - 2,
                       static_cast<int>(box.y + box.height) - 2};
    EXPECT_NE(differences(golden_png, moved(drawn, label, 1, 0), check), "");
    EXPECT_NE(differences(golden_png, moved(drawn, label, 0, 1), check), "");
    // One letter of the clef's name.
    Score renamed = figure.score;
    renamed.clefs[0].id = "fog23";
    renamed.bars[0].clef = "fog23";
    const StaffPicture other(renamed);
    EXPECT_NE(differences(golden_png, patched(drawn, Image::of(other), label), check), "");
    // A rasteriser that draws text a tenth lighter still shows the same picture; one that
    // draws it a third lighter does not.
    const auto faded = [&](double alpha) {
        const pictures::SurfacePtr surface(
            cairo_image_surface_create(CAIRO_FORMAT_ARGB32, drawn.width(), drawn.height()),
            &cairo_surface_destroy);
        const pictures::CairoPtr cairo(cairo_create(surface.get()), &cairo_destroy);
        cairo_set_source_rgb(cairo.get(), 1, 1, 1);
        cairo_paint(cairo.get());
        picture.draw(cairo.get(), pictures::all_layers & ~picture.text_layers());
        cairo_push_group(cairo.get());
        picture.draw(cairo.get(), picture.text_layers());
        cairo_pop_group_to_source(cairo.get());
        cairo_paint_with_alpha(cairo.get(), alpha);
        return Image(surface.get());
    };
    EXPECT_EQ(differences(golden_png, faded(1.0), check), "");
    EXPECT_EQ(differences(golden_png, faded(0.9), check), "");
    EXPECT_NE(differences(golden_png, faded(0.67), check), "");
}

TEST(GoldenComparison, FailsWhenTheEnvelopeOrABarLabelMovesOrVanishes) {
    const auto pictures = shipped("..") / "docs" / "pictures";
    const auto golden_png = pictures / "ode-to-joy-signal.png";
    const auto bundle = load_score_file(shipped("ode-to-joy.score.xml"));
    const render::Performance performance(bundle);
    const SignalPicture picture(performance, bundle.score.title);
    const auto drawn = Image::of(picture);
    const testing::GoldenCheck check(picture);
    ASSERT_EQ(differences(golden_png, drawn, check), "");
    // The envelope over the first bar, a pixel up, or gone.
    const int x0 = static_cast<int>(picture.x_of(0.0)) + 2;
    const int x1 = static_cast<int>(picture.x_of(1.0));
    const Window plot{x0, static_cast<int>(picture.y_of(performance.peak_amplitude())) - 3, x1,
                      static_cast<int>(picture.y_of(-performance.peak_amplitude())) + 3};
    EXPECT_NE(differences(golden_png, moved(drawn, plot, 0, -1), check), "");
    EXPECT_NE(
        differences(
            golden_png,
            patched(drawn, Image::of(picture, pictures::all_layers & ~SignalPicture::envelope),
                    plot),
            check),
        "");
    // The label "bar 2", a pixel to the right, or gone.
    const int bar2 = static_cast<int>(picture.x_of(performance.timeline().at(4).onset));
    ASSERT_EQ(performance.timeline().at(4).bar, 1u);
    const Window label{bar2 + 2, 30, bar2 + 40, 46};
    EXPECT_NE(differences(golden_png, moved(drawn, label, 1, 0), check), "");
    EXPECT_NE(
        differences(
            golden_png,
            patched(drawn, Image::of(picture, pictures::all_layers & ~SignalPicture::bar_labels),
                    label),
            check),
        "");
}

// --- Signal --------------------------------------------------------------------------------

TEST(SignalPicture, DrawsTheSignalWhereNotesSoundAndNothingInRests) {
    const auto bundle = load_score_file(golden("figure-2-3a.score.xml"));
    const render::Performance performance(bundle);
    const SignalPicture picture(performance, "Fig. 2.3c");
    const auto image = Image::of(picture);
    EXPECT_EQ(image.width(), 960);
    EXPECT_EQ(image.height(), 320);
    // Fig. 2.3c: an 8th at amplitude 1, a quarter at 2, an 8th rest, a half at 2 (tempo 1 s).
    const auto inked_column = [&](double t, double level) {
        int inked = 0;
        for (int dx = -3; dx <= 3; ++dx) {
            inked += image.at(static_cast<int>(picture.x_of(t) + dx),
                              static_cast<int>(picture.y_of(level)))
                             .white()
                         ? 0
                         : 1;
        }
        return inked;
    };
    EXPECT_GT(inked_column(1.0, 1.0), 0);   // inside the quarter at amplitude 2
    EXPECT_GT(inked_column(3.0, -1.5), 0);  // inside the half note
    EXPECT_EQ(inked_column(1.75, 1.0), 0);  // the 8th rest is silence
    EXPECT_EQ(inked_column(0.25, 1.5), 0);  // the first 8th never reaches 1.5
}

const std::vector<NamedLayer> kSignalLayers{
    {SignalPicture::title, "the title"},
    {SignalPicture::legend, "the legend's lines"},
    {SignalPicture::legend_text, "the legend's text"},
    {SignalPicture::frame, "the frame and ticks"},
    {SignalPicture::axis_labels, "the axis labels"},
    {SignalPicture::bar_boundaries, "the bar boundaries"},
    {SignalPicture::bar_labels, "the bar labels"},
    {SignalPicture::note_boundaries, "the note boundaries"},
    {SignalPicture::signal, "the signal"},
    {SignalPicture::envelope, "the envelope"},
};

// The plot's lines cross each other and end on its frame.
const std::set<std::pair<Layers, Layers>> kSignalMayMeet{
    {SignalPicture::frame, SignalPicture::bar_boundaries},
    {SignalPicture::frame, SignalPicture::note_boundaries},
    {SignalPicture::frame, SignalPicture::signal},
    {SignalPicture::frame, SignalPicture::envelope},
    {SignalPicture::signal, SignalPicture::envelope},
    {SignalPicture::signal, SignalPicture::bar_boundaries},
    {SignalPicture::signal, SignalPicture::note_boundaries},
    {SignalPicture::envelope, SignalPicture::bar_boundaries},
    {SignalPicture::envelope, SignalPicture::note_boundaries},
};

// Bars of every width: four whole notes, ten dotted 8ths, sixty 32nds (too narrow for any label).
ScoreBundle bars_of_every_width(const std::string& title) {
    std::string bars;
    for (int b = 0; b < 4; ++b) {
        bars += R"(<Bar clef="c"><Note length="whole" number="2" string="1"/></Bar>)";
    }
    for (int b = 0; b < 10; ++b) {
        bars += R"(<Bar clef="c"><Note length="8th_dot" number="1" string="2"/></Bar>)";
    }
    for (int b = 0; b < 60; ++b) {
        bars += R"(<Bar clef="c"><Note length="32th" number="2" string="3"/></Bar>)";
    }
    return testing::bundle_from("<VibScore version=\"1.0\"><Title>" + title +
                                    "</Title><Clef id=\"c\" href=\"c.xml\"/>" + bars +
                                    "</VibScore>",
                                {{"c.xml", testing::sine_clef(0.5, {100, 150, 200}, {0.5, 1.0})}});
}

TEST(SignalPicture, KeepsBarLabelsOffTheSignalAndEveryMarkApart) {
    const auto ode = load_score_file(shipped("ode-to-joy.score.xml"));
    const auto elise = fur_elise();  // its waveform reaches full scale
    const auto crowded = testing::bundle_from(
        R"(<VibScore version="1.0"><Title>Crowded</Title><Clef id="c" href="c.xml"/>)" +
            std::string(R"(<Bar clef="c"><Note length="half" number="3" string="6" )"
                        R"(dynamics="crescendo"/><Note length="half" number="3" string="6" )"
                        R"(dynamics="decrescendo"/></Bar>)") +
            "</VibScore>",
        {{"c.xml", testing::sine_clef(0.5, {100, 200, 300, 400, 500, 600}, {0.2, 0.5, 1.0})}});
    const auto narrow = bars_of_every_width(
        "A title so long that it would run into the legend at the top right of the picture "
        "unless it were cut short");
    Layers inked = 0;
    for (const auto* bundle : {&ode, &elise, &crowded, &narrow}) {
        SCOPED_TRACE(bundle->score.title);
        const render::Performance performance(*bundle);
        inked |= expect_apart(SignalPicture(performance, bundle->score.title), kSignalLayers,
                              kSignalMayMeet);
    }
    expect_every_layer_checked(inked, kSignalLayers);
}

TEST(SignalPicture, NumbersEachBarWithinItsOwnWidth) {
    const auto bundle = bars_of_every_width("Narrow bars");
    const render::Performance performance(bundle);
    const SignalPicture picture(performance, "Narrow bars");
    const auto labels = Image::ink_of(picture, SignalPicture::bar_labels);
    std::vector<double> starts;
    for (const auto& timing : performance.timeline()) {
        if (starts.size() == timing.bar) {
            starts.push_back(picture.x_of(timing.onset));
        }
    }
    ASSERT_EQ(starts.size(), 74u);
    // Ink in the label row from a bar's start up to the next: whether its label is there.
    const auto labelled = [&](std::size_t bar) {
        const double end =
            bar + 1 < starts.size() ? starts[bar + 1] : picture.x_of(performance.duration());
        for (int x = static_cast<int>(starts[bar]); x < static_cast<int>(end); ++x) {
            for (int y = 0; y < labels.height(); ++y) {
                if (labels.at(x, y).a > 0) {
                    return true;
                }
            }
        }
        return false;
    };
    // No label reaches across the start of the next bar.
    for (const double x : starts) {
        for (int y = 0; y < labels.height(); ++y) {
            ASSERT_EQ(labels.at(static_cast<int>(std::round(x)), y).a, 0) << x << "," << y;
        }
    }
    for (std::size_t bar = 0; bar < 14; ++bar) {
        EXPECT_TRUE(labelled(bar)) << "bar " << bar + 1;  // "bar 1" .. "bar 4", "5" .. "14"
    }
    for (std::size_t bar = 14; bar < 74; ++bar) {
        EXPECT_FALSE(labelled(bar)) << "bar " << bar + 1;  // 4 pixels wide
    }
}

// --- Actuator response ---------------------------------------------------------------------

render::ActuatorResponse response_of(const render::Performance& performance,
                                     const actuator::Declaration& declared) {
    render::ResponseOptions options;
    options.reverse = declared.brake == actuator::Brake::reverse;
    return render::actuator_response(performance, declared, options);
}

// The docs' picture of a tacton on that ERM (docs/drivers.md).
constexpr const char* kResponseDocScore = "notification-message.score.xml";
constexpr const char* kResponseDocPicture = "notification-message-on-erm.png";

// One score and the picture of what an actuator makes of it, kept together.
struct Felt {
    ScoreBundle bundle;
    render::Performance performance{bundle};
    render::ActuatorResponse response;
    ResponsePicture picture;
    Felt(ScoreBundle b, const actuator::Declaration& declared, const std::string& title)
        : bundle(std::move(b)),
          response(response_of(performance, declared)),
          picture(performance, response, title,
                  "on the actuator: " + actuator::describe(declared) + "\n" +
                      written_clefs(bundle).first,
                  written_clefs(bundle).second) {}
};

const std::vector<NamedLayer> kResponseLayers{
    {ResponsePicture::title, "the title"},
    {ResponsePicture::caption, "the caption"},
    {ResponsePicture::legend, "the legend's lines"},
    {ResponsePicture::legend_text, "the legend's text"},
    {ResponsePicture::bar_labels, "the bar numbers and clef names"},
    {ResponsePicture::frame, "the frame and ticks"},
    {ResponsePicture::axis_labels, "the axis labels"},
    {ResponsePicture::bar_boundaries, "the bar boundaries"},
    {ResponsePicture::written, "the written strength"},
    {ResponsePicture::uncompensated, "the uncompensated strength"},
    {ResponsePicture::compensated, "the compensated strength"},
};

// The traces run together where the actuator follows the score, and across the bar lines; all
// of them start and end on the frame.
const std::set<std::pair<Layers, Layers>> kResponseMayMeet{
    {ResponsePicture::frame, ResponsePicture::bar_boundaries},
    {ResponsePicture::frame, ResponsePicture::written},
    {ResponsePicture::frame, ResponsePicture::uncompensated},
    {ResponsePicture::frame, ResponsePicture::compensated},
    {ResponsePicture::written, ResponsePicture::uncompensated},
    {ResponsePicture::written, ResponsePicture::compensated},
    {ResponsePicture::uncompensated, ResponsePicture::compensated},
    {ResponsePicture::bar_boundaries, ResponsePicture::written},
    {ResponsePicture::bar_boundaries, ResponsePicture::uncompensated},
    {ResponsePicture::bar_boundaries, ResponsePicture::compensated},
};

// How much ink of `layer` lies within `radius` pixels of where strength s is drawn at time t.
int ink_near(const Image& ink, const ResponsePicture& picture, double t, double s, int radius = 1) {
    int total = 0;
    const int x = static_cast<int>(std::lround(picture.x_of(t)));
    const int y = static_cast<int>(std::lround(picture.y_of(s)));
    for (int dx = -radius; dx <= radius; ++dx) {
        for (int dy = -radius; dy <= radius; ++dy) {
            total += ink.at(x + dx, y + dy).a;
        }
    }
    return total;
}

TEST(ResponsePicture, DrawsEachStrengthWhereItIsInItsOwnLayer) {
    const Felt felt(load_score_file(shipped("alarm.score.xml")), example_erm(), "alarm");
    const auto& picture = felt.picture;
    EXPECT_EQ(Image::of(picture).width(), 960);
    EXPECT_EQ(Image::of(picture).height(), 400);
    const struct {
        ResponsePicture::Layer layer;
        const std::vector<double>& values;
    } traces[] = {{ResponsePicture::written, felt.response.written},
                  {ResponsePicture::uncompensated, felt.response.uncompensated},
                  {ResponsePicture::compensated, felt.response.compensated}};
    for (const auto& trace : traces) {
        const auto ink = Image::ink_of(picture, trace.layer);
        // Every 50 ms, the trace passes where its strength is: within 3 pixels, the gap of the
        // uncompensated trace's dashes, so that a gap cannot fall on the very spot.
        for (std::size_t k = 0; k < trace.values.size(); k += 50) {
            const double t = static_cast<double>(k) / felt.response.rate_hz;
            EXPECT_GT(ink_near(ink, picture, t, trace.values[k], 3), 0)
                << "layer " << trace.layer << " at " << t << " s";
        }
    }
    // The picture shows the ringing after the score, and strength 1 (the rated drive) fits.
    EXPECT_GT(picture.span(), felt.performance.duration() + 0.25);
    EXPECT_GT(picture.top(), 1.0);
}

TEST(ResponsePicture, ShowsTheUncompensatedErmRingingOnWhereTheCompensatedOneStops) {
    const Felt felt(load_score_file(shipped(kResponseDocScore)), example_erm(), "message");
    const double at = felt.performance.duration() + 0.04;
    const auto off = Image::ink_of(felt.picture, ResponsePicture::uncompensated);
    const auto on = Image::ink_of(felt.picture, ResponsePicture::compensated);
    // 40 ms after the end the coasting motor is still felt; the braked one is at rest.
    const auto k = static_cast<std::size_t>(std::lround(at * felt.response.rate_hz));
    ASSERT_GT(felt.response.uncompensated.at(k), 0.08);
    ASSERT_LT(felt.response.compensated.at(k), 0.01);
    EXPECT_GT(ink_near(off, felt.picture, at, felt.response.uncompensated[k]), 0);
    EXPECT_EQ(ink_near(on, felt.picture, at, felt.response.uncompensated[k]), 0);
    EXPECT_GT(ink_near(on, felt.picture, at, 0.0), 0);
}

// Pixels of `image` within a few levels of `ink`.
int pixels_of(const Image& image, const double* ink) {
    int count = 0;
    for (int x = 0; x < image.width(); ++x) {
        for (int y = 0; y < image.height(); ++y) {
            const auto pixel = image.at(x, y);
            const auto near = [](int level, double share) {
                return std::abs(level - static_cast<int>(std::lround(share * 255))) <= 8;
            };
            count += near(pixel.r, ink[0]) && near(pixel.g, ink[1]) && near(pixel.b, ink[2]);
        }
    }
    return count;
}

TEST(ResponsePicture, TellsTheThreeTracesApartByColourAndTheLegendShowsEach) {
    const Felt felt(load_score_file(shipped("alarm.score.xml")), example_erm(), "alarm");
    const double* inks[] = {ResponsePicture::written_ink, ResponsePicture::uncompensated_ink,
                            ResponsePicture::compensated_ink};
    const ResponsePicture::Layer traces[] = {
        ResponsePicture::written, ResponsePicture::uncompensated, ResponsePicture::compensated};
    const auto legend = Image::of(felt.picture, ResponsePicture::legend);
    for (std::size_t i = 0; i < 3; ++i) {
        const double* ink = inks[i];
        // Its line in the legend, and its trace in the plot, in its colour and no other's.
        EXPECT_GE(pixels_of(legend, ink), 10) << "trace " << i;
        EXPECT_GE(pixels_of(Image::of(felt.picture, traces[i]), ink), 100) << "trace " << i;
        for (std::size_t j = 0; j < 3; ++j) {
            if (j != i) {
                EXPECT_EQ(pixels_of(Image::of(felt.picture, traces[i]), inks[j]), 0)
                    << "trace " << i << " in the colour of " << j;
            }
        }
    }
}

// The legend names every line in the plot: the dashed bar and end lines too, each in its own
// colour; along the top each bar's number, and its clef where it changes, all above the plot.
TEST(ResponsePicture, TheLegendShowsTheDashedLinesAndTheBarsAreLabelledAboveThePlot) {
    const Felt felt(load_score_file(shipped("alarm.score.xml")), example_erm(), "alarm");
    const auto legend = Image::of(felt.picture, ResponsePicture::legend);
    EXPECT_GE(pixels_of(legend, ResponsePicture::bar_line_ink), 8);
    EXPECT_GE(pixels_of(legend, ResponsePicture::end_line_ink), 8);
    const auto labels = Image::ink_of(felt.picture, ResponsePicture::bar_labels);
    const int plot_top = static_cast<int>(std::floor(felt.picture.y_of(felt.picture.top())));
    int above = 0, inside = 0;
    for (int x = 0; x < labels.width(); ++x) {
        for (int y = 0; y < labels.height(); ++y) {
            (y < plot_top ? above : inside) += labels.at(x, y).a > 0 ? 1 : 0;
        }
    }
    EXPECT_GT(above, 30);  // "1 lra-phone" at least
    EXPECT_EQ(inside, 0);
    // The labels start at the first bar, at the left of the plot.
    int first = labels.width();
    for (int x = 0; x < labels.width() && first == labels.width(); ++x) {
        for (int y = 0; y < plot_top; ++y) {
            if (labels.at(x, y).a > 0) {
                first = x;
                break;
            }
        }
    }
    EXPECT_NEAR(first, felt.picture.x_of(0.0), 6);
}

TEST(ResponsePicture, KeepsEveryMarkApart) {
    const actuator::Declaration lra = example_lra();
    Layers inked = 0;
    {
        const Felt felt(load_score_file(shipped("alarm.score.xml")), example_erm(), "alarm");
        inked |= expect_apart(felt.picture, kResponseLayers, kResponseMayMeet);
    }
    {
        const Felt felt(load_score_file(shipped("ode-to-joy.score.xml")), lra,
                        "A title so long that it would run into the legend at the top right of "
                        "the picture unless it were cut short");
        inked |= expect_apart(felt.picture, kResponseLayers, kResponseMayMeet);
    }
    expect_every_layer_checked(inked, kResponseLayers);
}

TEST(GoldenComparison, FailsWhenTheCompensatedStrengthMovesOrVanishes) {
    const auto golden_png = shipped("..") / "docs" / "pictures" / kResponseDocPicture;
    const Felt felt(load_score_file(shipped(kResponseDocScore)), example_erm(),
                    load_score_file(shipped(kResponseDocScore)).score.title);
    const auto drawn = Image::of(felt.picture);
    const testing::GoldenCheck check(felt.picture);
    ASSERT_EQ(differences(golden_png, drawn, check), "");
    const Window plot{static_cast<int>(felt.picture.x_of(0.0)) + 2,
                      static_cast<int>(felt.picture.y_of(felt.picture.top())) + 2,
                      static_cast<int>(felt.picture.x_of(felt.picture.span())) - 2,
                      static_cast<int>(felt.picture.y_of(0.0)) - 2};
    EXPECT_NE(differences(golden_png, moved(drawn, plot, 1, 0), check), "");
    EXPECT_NE(differences(golden_png,
                          patched(drawn,
                                  Image::of(felt.picture,
                                            pictures::all_layers & ~ResponsePicture::compensated),
                                  plot),
                          check),
              "");
}

// --- Clef ----------------------------------------------------------------------------------

using pictures::ClefPicture;

Clef shipped_clef(const std::string& name) {
    return load_clef_file(shipped(name + ".clef.xml"));
}

// Whether a layer holds ink within a pixel or two of (x, y).
bool inked_near(const Image& ink, double x, double y, int reach = 1) {
    for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
            if (ink.at(static_cast<int>(x) + dx, static_cast<int>(y) + dy).a >= 64) {
                return true;
            }
        }
    }
    return false;
}

TEST(ClefPicture, DrawsEachSineStringAtItsFrequencyAndEachNumberAtItsAmplitude) {
    const auto clef = shipped_clef("lra-phone");
    const ClefPicture picture(clef, "lra-phone");
    ASSERT_EQ(picture.plots().size(), 1u);
    const auto& plot = picture.plots().front();
    const auto strings = Image::ink_of(picture, ClefPicture::strings);
    const auto numbers = Image::ink_of(picture, ClefPicture::numbers);
    const auto notes = Image::ink_of(picture, ClefPicture::notes);
    const double middle = plot.top + plot.height / 2;
    for (std::size_t s = 0; s < clef.strings.size(); ++s) {
        const double x = plot.x_of(clef.strings[s].frequency);
        EXPECT_TRUE(inked_near(strings, x, middle, 0)) << "string " << s + 1;
        // Nothing between two strings.
        if (s + 1 < clef.strings.size()) {
            const double between =
                plot.x_of((clef.strings[s].frequency + clef.strings[s + 1].frequency) / 2);
            EXPECT_FALSE(inked_near(strings, between, middle, 3)) << "after string " << s + 1;
        }
        for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
            // A note on every string at every number.
            EXPECT_TRUE(inked_near(notes, x, plot.y_of(clef.numbers[n]), 0))
                << "string " << s + 1 << ", number " << n + 1;
        }
    }
    for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
        const double y = plot.y_of(clef.numbers[n]);
        // Dashed: ink along the line, in at least a third of its pixels.
        int inked = 0;
        for (int x = static_cast<int>(plot.left) + 2; x < plot.left + plot.width - 2; ++x) {
            inked += numbers.at(x, static_cast<int>(std::round(y))).a >= 64 ? 1 : 0;
        }
        EXPECT_GT(inked, plot.width / 3) << "number " << n + 1;
        EXPECT_FALSE(inked_near(numbers, plot.left + plot.width / 2, y + 6, 1))
            << "below number " << n + 1;
    }
    // Number 9 (1.0) is higher than number 1 (0.2), string 6 (235 Hz) right of string 1.
    EXPECT_LT(plot.y_of(clef.numbers[8]), plot.y_of(clef.numbers[0]));
    EXPECT_GT(plot.x_of(clef.strings[5].frequency), plot.x_of(clef.strings[0].frequency));
}

TEST(ClefPicture, DrawsEachShapeStringsWaveformThroughItsControlPoints) {
    for (const char* name : {"soft-shapes", "erm-rough"}) {
        SCOPED_TRACE(name);
        const auto clef = shipped_clef(name);
        const ClefPicture picture(clef, name);
        ASSERT_EQ(picture.plots().size(), clef.strings.size());
        // String 6 on top, as on the staff.
        EXPECT_LT(picture.plots().back().top, picture.plots().front().top);
        const auto waveforms = Image::ink_of(picture, ClefPicture::strings);
        const auto points = Image::ink_of(picture, ClefPicture::points);
        for (std::size_t s = 0; s < clef.strings.size(); ++s) {
            const auto& plot = picture.plots()[s];
            for (const auto& point : clef.strings[s].points) {
                const double x = plot.x_of(point.time * clef.tempo), y = plot.y_of(point.level);
                EXPECT_TRUE(inked_near(points, x, y)) << "string " << s + 1 << " " << point.time;
                EXPECT_TRUE(inked_near(waveforms, x, y)) << "string " << s + 1 << " " << point.time;
            }
            // Between the points too, the waveform is where the renderer's is.
            const render::Waveform waveform(clef.type, clef.strings[s].points);
            for (double tau = 0.013; tau < 1.0; tau += 0.05) {
                EXPECT_TRUE(inked_near(waveforms, plot.x_of(tau * clef.tempo),
                                       plot.y_of(waveform.level(tau)), 2))
                    << "string " << s + 1 << " at " << tau;
            }
        }
    }
    // Where soft-shapes' string 5 has died away (level 0 from tau 0.25), nothing is drawn high.
    const auto clef = shipped_clef("soft-shapes");
    const ClefPicture picture(clef, "soft-shapes");
    const auto waveforms = Image::ink_of(picture, ClefPicture::strings);
    const auto& plot = picture.plots()[4];
    EXPECT_FALSE(inked_near(waveforms, plot.x_of(0.6 * clef.tempo), plot.y_of(0.5), 3));
    EXPECT_TRUE(inked_near(waveforms, plot.x_of(0.6 * clef.tempo), plot.y_of(0.0), 1));
}

const std::vector<NamedLayer> kClefLayers{
    {ClefPicture::title, "the title"},     {ClefPicture::frames, "the frames"},
    {ClefPicture::axis_labels, "labels"},  {ClefPicture::strings, "the strings"},
    {ClefPicture::numbers, "the numbers"}, {ClefPicture::notes, "the notes"},
    {ClefPicture::points, "the points"},   {ClefPicture::table, "the table"},
};

// Lines cross lines and end on frames; notes sit where strings and numbers cross; control
// points sit on their waveform, some on a frame's edge.
const std::set<std::pair<Layers, Layers>> kClefMayMeet{
    {ClefPicture::frames, ClefPicture::strings}, {ClefPicture::frames, ClefPicture::numbers},
    {ClefPicture::frames, ClefPicture::points},  {ClefPicture::strings, ClefPicture::numbers},
    {ClefPicture::strings, ClefPicture::notes},  {ClefPicture::numbers, ClefPicture::notes},
    {ClefPicture::strings, ClefPicture::points},
};

TEST(ClefPicture, KeepsEveryMarkApart) {
    Layers inked = 0;
    for (const char* name : {"lra-phone", "shaker-sine-low", "soft-shapes", "erm-rough",
                             "pattern-ms", "shaker-sine-linear"}) {
        SCOPED_TRACE(name);
        const auto clef = shipped_clef(name);
        inked |= expect_apart(ClefPicture(clef, name), kClefLayers, kClefMayMeet);
    }
    // Strings a hertz apart and numbers a thousandth apart: their labels make room.
    const auto crowded = read_clef(testing::sine_clef(1, {100, 101, 102, 150, 151, 300},
                                                      {0.001, 0.002, 0.003, 0.5, 0.501, 1.0}),
                                   "crowded");
    inked |= expect_apart(ClefPicture(crowded, "crowded"), kClefLayers, kClefMayMeet);
    expect_every_layer_checked(inked, kClefLayers);
}

TEST(ClefPicture, ShowDrawsAClefByFileOrByName) {
    TempDir dir;
    const auto vibscore = testing::required_env("VIBSCORE");
    // No vibscored to ask: a name that is no registry score is looked up as a clef.
    const std::vector<std::string> no_bus{"/usr/bin/env",
                                          "DBUS_SYSTEM_BUS_ADDRESS=unix:path=/nonexistent"};
    const auto png = (dir.path() / "clef.png").string(), svg = (dir.path() / "clef.svg").string();
    auto result = testing::run_command(
        {vibscore, "show", shipped("lra-phone.clef.xml").string(), "--png", png, "--svg", svg});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto clef = shipped_clef("lra-phone");
    const ClefPicture picture(clef, "lra-phone.clef.xml");
    EXPECT_EQ(testing::GoldenCheck(picture).differences(Image::of(picture), Image::read_png(png)),
              "");
    pugi::xml_document document;
    EXPECT_TRUE(document.load_file(svg.c_str()));

    auto by_name = no_bus;
    for (const auto& word :
         {vibscore, std::string("show"), std::string("erm-rough"), std::string("--clefs"),
          shipped("").string(), std::string("--png"), png}) {
        by_name.push_back(word);
    }
    result = testing::run_command(by_name);
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(Image::read_png(png).height(),
              static_cast<int>(ClefPicture(shipped_clef("erm-rough"), "erm-rough").height()));

    auto unknown = no_bus;
    for (const auto& word :
         {vibscore, std::string("show"), std::string("no-such-thing"), std::string("--clefs"),
          shipped("").string(), std::string("--png"), png}) {
        unknown.push_back(word);
    }
    result = testing::run_command(unknown);
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.err.find("no clef \"no-such-thing\" in " + shipped("").string()),
              std::string::npos)
        << result.err;
}

// --- Clef over an actuator's response ------------------------------------------------------

bool has_ink(const Image& ink) {
    for (int y = 0; y < ink.height(); ++y) {
        for (int x = 0; x < ink.width(); ++x) {
            if (ink.at(x, y).a >= 64) {
                return true;
            }
        }
    }
    return false;
}

actuator::Declaration declared_in(const std::string& example) {
    const auto declared = daemon::load_config(shipped("../examples/actuator/" + example)).actuator;
    EXPECT_TRUE(declared) << example;
    return declared.value_or(actuator::Declaration{});
}

TEST(ClefPicture, DrawsAnLrasResponseBehindASineClefAndWhatEachNumberReaches) {
    const auto clef = shipped_clef("lra-phone");
    const auto lra = declared_in("lra.conf");
    const ClefPicture picture(clef, "lra-phone", lra);
    const auto& plot = picture.plots().front();
    // The response: the model's strength at full drive, 1 / rated-drive at resonance.
    EXPECT_NEAR(picture.full_drive_strength(175.0), 1.0 / 0.7, 1e-9);
    EXPECT_NEAR(picture.full_drive_strength(235.0),
                actuator::Physics(lra).steady_strength({1.0, 235.0}), 1e-12);
    // Its peak is inside the plot, not cut off.
    EXPECT_LT(plot.y_to, 1.0 / 0.7 * 1.2);
    EXPECT_GT(plot.y_to, 1.0 / 0.7);
    const auto response = Image::ink_of(picture, ClefPicture::response);
    for (double f = plot.x_from + 1.0; f < plot.x_to - 1.0; f += 2.5) {
        EXPECT_TRUE(
            inked_near(response, plot.x_of(f), plot.y_of(picture.full_drive_strength(f)), 2))
            << f << " Hz";
    }
    // Far off resonance the curve is low: nothing where full strength would be.
    EXPECT_FALSE(inked_near(response, plot.x_of(235.0), plot.y_of(1.0), 4));
    EXPECT_TRUE(inked_near(response, plot.x_of(175.0), plot.y_of(1.0 / 0.7), 2));

    // What each number reaches: near resonance every number (compensation drives harder off it);
    // at 235 Hz full drive gives less than number 1 asks, so every number reaches only that.
    const auto reached = Image::ink_of(picture, ClefPicture::reached);
    const double at_235 = picture.full_drive_strength(235.0);
    ASSERT_LT(at_235, clef.numbers.front());
    for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
        EXPECT_NEAR(picture.reached_strength(1, n), clef.numbers[n], 1e-9) << "number " << n + 1;
        EXPECT_NEAR(picture.reached_strength(5, n), at_235, 1e-9) << "number " << n + 1;
    }
    for (std::size_t s = 0; s < clef.strings.size(); ++s) {
        const double x = plot.x_of(clef.strings[s].frequency);
        for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
            // The bar reaches past the note's dot on both sides.
            const double y = plot.y_of(picture.reached_strength(s, n));
            EXPECT_TRUE(inked_near(reached, x - 5, y, 1)) << "string " << s + 1 << " " << n + 1;
            EXPECT_TRUE(inked_near(reached, x + 5, y, 1)) << "string " << s + 1 << " " << n + 1;
        }
    }
    const double x6 = plot.x_of(235.0);
    EXPECT_FALSE(inked_near(reached, x6 + 5, plot.y_of(clef.numbers.front()), 3));
    EXPECT_FALSE(inked_near(reached, x6 + 5, plot.y_of(1.0), 3));

    // Without compensation the renderer drives number x rated-drive at any frequency: each
    // number reaches its share of the gain there.
    auto uncompensated = lra;
    uncompensated.compensation = false;
    const ClefPicture plain(clef, "lra-phone", uncompensated);
    const double gain_235 = actuator::Physics::lra_gain(235.0, 175.0, 15.0);
    EXPECT_NEAR(plain.reached_strength(5, 0), 0.2 * gain_235, 1e-9);
    EXPECT_NEAR(plain.reached_strength(5, 8), 1.0 * gain_235, 1e-9);
    EXPECT_LT(plain.reached_strength(5, 0), plain.reached_strength(5, 8));
}

// Where a number reaches just what it asks (near resonance), its mark lies on its dot: the mark
// is drawn over it, so the picture shows it there and not only the dot.
TEST(ClefPicture, WhatANumberReachesIsSeenOverItsDot) {
    const auto clef = shipped_clef("lra-phone");
    const ClefPicture picture(clef, "lra-phone", declared_in("lra.conf"));
    const auto& plot = picture.plots().front();
    const auto drawn = Image::of(picture);
    for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
        ASSERT_NEAR(picture.reached_strength(1, n), clef.numbers[n], 1e-9);
        const int x = static_cast<int>(std::lround(plot.x_of(clef.strings[1].frequency)));
        const int y = static_cast<int>(std::lround(plot.y_of(clef.numbers[n])));
        int marked = 0;
        for (int dx = -2; dx <= 2; ++dx) {
            const auto pixel = drawn.at(x + dx, y);
            marked += std::abs(pixel.r - 217) <= 10 && std::abs(pixel.g - 77) <= 10 &&
                      std::abs(pixel.b - 13) <= 10;
        }
        EXPECT_GE(marked, 3) << "number " << n + 1 << ": its dot hides its mark";
    }
    EXPECT_EQ(std::lround(ClefPicture::reached_ink[0] * 255), 217);
}

TEST(ClefPicture, WithoutAnActuatorDrawsNoResponseNoBarsAndNoCaption) {
    const auto clef = shipped_clef("lra-phone");
    const ClefPicture picture(clef, "lra-phone");
    const auto with = ClefPicture(clef, "lra-phone", declared_in("lra.conf"));
    for (const auto layer : {ClefPicture::response, ClefPicture::reached, ClefPicture::caption}) {
        EXPECT_FALSE(has_ink(Image::ink_of(picture, layer))) << layer;
        EXPECT_TRUE(has_ink(Image::ink_of(with, layer))) << layer;
    }
    // The caption takes room of its own below the plot.
    EXPECT_GT(with.height(), picture.height());
}

TEST(ClefPicture, SaysAnErmHasNoPitchAndDrawsNoResponseCurve) {
    const auto clef = shipped_clef("lra-phone");
    const auto erm = declared_in("erm.conf");
    const ClefPicture picture(clef, "lra-phone", erm);
    const auto& plot = picture.plots().front();
    EXPECT_FALSE(has_ink(Image::ink_of(picture, ClefPicture::response)));
    const auto caption = Image::ink_of(picture, ClefPicture::caption);
    EXPECT_TRUE(has_ink(caption));
    // Two lines: the declaration, and that the ERM has no pitch. The caption is below the plot.
    int first = caption.height(), last = -1;
    for (int y = 0; y < caption.height(); ++y) {
        for (int x = 0; x < caption.width(); ++x) {
            if (caption.at(x, y).a >= 64) {
                first = std::min(first, y);
                last = std::max(last, y);
            }
        }
    }
    EXPECT_GT(first, plot.top + plot.height);
    EXPECT_GT(last - first, 20);
    // Full drive of a rated-drive 0.7 ERM gives 1.43 at any frequency: every number is reached.
    for (std::size_t s = 0; s < clef.strings.size(); ++s) {
        for (std::size_t n = 0; n < clef.numbers.size(); ++n) {
            EXPECT_NEAR(picture.reached_strength(s, n), clef.numbers[n], 1e-9);
        }
    }
}

const std::vector<NamedLayer> kActuatorClefLayers{
    {ClefPicture::title, "the title"},       {ClefPicture::frames, "the frames"},
    {ClefPicture::axis_labels, "labels"},    {ClefPicture::strings, "the strings"},
    {ClefPicture::numbers, "the numbers"},   {ClefPicture::notes, "the notes"},
    {ClefPicture::points, "the points"},     {ClefPicture::table, "the table"},
    {ClefPicture::response, "the response"}, {ClefPicture::reached, "the reached strengths"},
    {ClefPicture::caption, "the caption"},
};

// The response and the reached bars cross the clef's lines and notes, as those cross each other.
std::set<std::pair<Layers, Layers>> actuator_clef_may_meet() {
    auto meet = kClefMayMeet;
    for (const Layers layer :
         {ClefPicture::frames, ClefPicture::strings, ClefPicture::numbers, ClefPicture::notes}) {
        meet.insert({layer, ClefPicture::response});
        meet.insert({layer, ClefPicture::reached});
    }
    meet.insert({ClefPicture::response, ClefPicture::reached});
    return meet;
}

TEST(ClefPicture, KeepsEveryMarkApartOverAnActuator) {
    const auto meet = actuator_clef_may_meet();
    Layers inked = 0;
    for (const char* example : {"lra.conf", "erm.conf"}) {
        const auto declared = declared_in(example);
        for (const char* name : {"lra-phone", "shaker-sine-low", "soft-shapes", "erm-rough"}) {
            SCOPED_TRACE(std::string(name) + " on " + example);
            inked |= expect_apart(ClefPicture(shipped_clef(name), name, declared),
                                  kActuatorClefLayers, meet);
        }
    }
    expect_every_layer_checked(inked, kActuatorClefLayers);
}

TEST(ClefPicture, ShowDrawsAClefOverTheActuatorItIsGiven) {
    TempDir dir;
    const auto vibscore = testing::required_env("VIBSCORE");
    const auto lra_file = shipped("../examples/actuator/lra.conf").string();
    const auto png = (dir.path() / "clef.png").string();
    auto result = testing::run_command({vibscore, "show", shipped("lra-phone.clef.xml").string(),
                                        "--actuator", lra_file, "--png", png});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const auto clef = shipped_clef("lra-phone");
    const ClefPicture picture(clef, "lra-phone.clef.xml", declared_in("lra.conf"));
    EXPECT_EQ(testing::GoldenCheck(picture).differences(Image::of(picture), Image::read_png(png)),
              "");

    // A score has no strings to draw a response behind: render --actuator is the way.
    result =
        testing::run_command({vibscore, "show", shipped("notification-message.score.xml").string(),
                              "--actuator", lra_file, "--png", png});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("is a score (vibscore render"), std::string::npos) << result.err;
    // --actuator draws a picture only.
    result = testing::run_command(
        {vibscore, "show", shipped("lra-phone.clef.xml").string(), "--actuator", lra_file});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("give --svg FILE or --png FILE"), std::string::npos) << result.err;
    // A file declaring no actuator, or a bad one, is named.
    const auto bad = (dir.path() / "bad.conf").string();
    std::ofstream(bad) << "[actuator]\nkind = lra\nq = 0\n";
    result = testing::run_command({vibscore, "show", shipped("lra-phone.clef.xml").string(),
                                   "--actuator", bad, "--png", png});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("bad.conf:3"), std::string::npos) << result.err;
}

// The fitted clef the docs draw is what its documented command writes.
TEST(Pictures, TheFittedClefInTheDocsIsWhatItsCommandWrites) {
    TempDir dir;
    const auto root = shipped("..");
    std::istringstream text(testing::read_file(root / "docs/clefs.md"));
    int found = 0;
    for (std::string line; std::getline(text, line);) {
        const auto at = line.find("build/client/vibscore clef fit ");
        if (at == std::string::npos || line.find("-o docs/pictures/") == std::string::npos) {
            continue;
        }
        SCOPED_TRACE(line);
        ++found;
        std::vector<std::string> argv{testing::required_env("VIBSCORE")};
        std::istringstream words(line.substr(at + std::string("build/client/vibscore ").size()));
        std::string committed;
        for (std::string word; words >> word && word != "#";) {
            if (!argv.empty() && argv.back() == "-o") {
                committed = word;
                word = (dir.path() / "fitted.clef.xml").string();
            } else if (std::filesystem::exists(root / word)) {
                word = (root / word).string();
            }
            argv.push_back(word);
        }
        const auto result = testing::run_command(argv);
        ASSERT_EQ(result.exit_code, 0) << result.err;
        const auto written = load_clef_file(dir.path() / "fitted.clef.xml");
        const auto shown = load_clef_file(root / committed);
        // Equal within rounding: another libm may differ in the last digit.
        ASSERT_EQ(written.type, shown.type);
        EXPECT_NEAR(written.tempo, shown.tempo, 1e-12);
        ASSERT_EQ(written.numbers.size(), shown.numbers.size());
        for (std::size_t n = 0; n < written.numbers.size(); ++n) {
            EXPECT_NEAR(written.numbers[n], shown.numbers[n], 1e-12);
        }
        ASSERT_EQ(written.strings.size(), shown.strings.size());
        for (std::size_t s = 0; s < written.strings.size(); ++s) {
            EXPECT_NEAR(written.strings[s].frequency, shown.strings[s].frequency, 1e-9);
            ASSERT_EQ(written.strings[s].points.size(), shown.strings[s].points.size());
            for (std::size_t p = 0; p < written.strings[s].points.size(); ++p) {
                EXPECT_NEAR(written.strings[s].points[p].time, shown.strings[s].points[p].time,
                            1e-9);
                EXPECT_NEAR(written.strings[s].points[p].level, shown.strings[s].points[p].level,
                            1e-9);
            }
        }
    }
    EXPECT_EQ(found, 1);
}

// A blank drawing of a given size.
class BlankDrawing : public pictures::Drawing {
  public:
    BlankDrawing(double width, double height) : width_(width), height_(height) {}
    double width() const override { return width_; }
    double height() const override { return height_; }
    void draw(cairo_t*, pictures::Layers) const override {}
    pictures::Layers text_layers() const override { return 0; }

  private:
    double width_, height_;
};

TEST(Pictures, APngIsAtMost32767PixelsOnASideAndATallerOneIsRefusedNamingItsSize) {
    TempDir dir;
    const auto png = dir.path() / "tall.png";
    pictures::write_picture(BlankDrawing(1, 32767), png);
    EXPECT_TRUE(std::filesystem::exists(png));
    pictures::write_picture(BlankDrawing(32767, 1), png);
    for (const auto& [width, height] : {std::pair{1.0, 32767.5}, std::pair{32768.0, 1.0}}) {
        const auto refused = dir.path() / "refused.png";
        try {
            pictures::write_picture(BlankDrawing(width, height), refused);
            ADD_FAILURE() << width << "x" << height << " was written";
        } catch (const std::runtime_error& error) {
            EXPECT_EQ(std::string(error.what()),
                      "the picture is " + std::to_string(static_cast<int>(std::ceil(width))) + "x" +
                          std::to_string(static_cast<int>(std::ceil(height))) +
                          " pixels, and an image is at most 32767 on a side: draw it as an SVG "
                          "(--svg), which has no such limit");
        }
        EXPECT_FALSE(std::filesystem::exists(refused));
        EXPECT_FALSE(std::filesystem::exists(dir.path() / "refused.png.partial"));
    }
}

TEST(Pictures, TheFileFormatComesFromTheExtension) {
    EXPECT_EQ(pictures::picture_format_for("a.svg"), pictures::PictureFormat::svg);
    EXPECT_EQ(pictures::picture_format_for("dir/a.png"), pictures::PictureFormat::png);
    EXPECT_THROW(pictures::picture_format_for("a.jpg"), std::invalid_argument);
}

}  // namespace
}  // namespace vibscore
