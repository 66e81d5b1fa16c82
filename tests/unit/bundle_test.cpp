#include <gtest/gtest.h>

#include "score/bundle.hpp"
#include "score/clef_xml.hpp"
#include "score/limits.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

using testing::bundle_from;
using testing::first_diagnostic;
using testing::one_clef_score;
using testing::sine_clef;
using testing::TempDir;

const std::string kClef = sine_clef(1.0, {100, 150, 200}, {1, 2});

TEST(Bundle, LoadsClefsRelativeToTheScoreFile) {
    TempDir dir;
    dir.write("clefs/c.xml", kClef);
    const auto path = dir.write("scores/s.xml",
                                "<VibScore><Clef id=\"c\" href=\"../clefs/c.xml\"/><Bar "
                                "clef=\"c\"><Note length=\"quarter\" "
                                "number=\"2\" string=\"3\"/></Bar></VibScore>");
    const auto bundle = load_score_file(path);
    EXPECT_EQ(bundle.file, path.string());
    EXPECT_EQ(bundle.clef_of(bundle.score.bars[0]).strings[2].frequency, 200.0);
}

// A lookup of registry clefs by name that knows only "lra-phone", recording what it was asked.
struct NamedClefs {
    std::vector<std::string> asked;
    NamedClefLookup lookup() {
        return {[this](const std::string& name) -> std::optional<NamedClef> {
                    asked.push_back(name);
                    if (name != "lra-phone") {
                        return std::nullopt;
                    }
                    return NamedClef{read_clef(sine_clef(0.5, {300}, {1}), "registry"), "registry"};
                },
                "the test's registry"};
    }
};

const std::string kNamedScore =
    "<VibScore><Clef id=\"c\" href=\"lra-phone.clef.xml\"/><Bar clef=\"c\"><Note "
    "length=\"quarter\" number=\"1\" string=\"1\"/></Bar></VibScore>";

TEST(Bundle, ABareClefNameWithNoFileBesideTheScoreIsLookedUpByName) {
    TempDir dir;
    const auto path = dir.write("s.score.xml", kNamedScore);
    NamedClefs named;
    std::map<std::string, std::string> origins;
    const auto bundle = load_score_file(path, named.lookup(), &origins);
    EXPECT_EQ(named.asked, std::vector<std::string>{"lra-phone"});
    EXPECT_EQ(bundle.clef_of(bundle.score.bars[0]).strings[0].frequency, 300.0);
    EXPECT_EQ(origins.at("c"), "registry");
}

TEST(Bundle, AClefFileBesideTheScoreWinsOverTheNamedOne) {
    TempDir dir;
    dir.write("lra-phone.clef.xml", kClef);
    const auto path = dir.write("s.score.xml", kNamedScore);
    NamedClefs named;
    std::map<std::string, std::string> origins;
    const auto bundle = load_score_file(path, named.lookup(), &origins);
    EXPECT_TRUE(named.asked.empty());
    EXPECT_EQ(bundle.clef_of(bundle.score.bars[0]).strings[0].frequency, 100.0);
    EXPECT_EQ(origins.at("c"), (dir.path() / "lra-phone.clef.xml").string());
}

TEST(Bundle, AHrefWithAFolderIsAPathNeverAName) {
    TempDir dir;
    const auto path = dir.write("s.score.xml",
                                "<VibScore><Clef id=\"c\" href=\"clefs/lra-phone.clef.xml\"/><Bar "
                                "clef=\"c\"/></VibScore>");
    NamedClefs named;
    const auto diagnostic = first_diagnostic([&] { load_score_file(path, named.lookup()); });
    EXPECT_TRUE(named.asked.empty());
    EXPECT_NE(diagnostic.message.find("cannot open"), std::string::npos) << diagnostic.message;
}

TEST(Bundle, ANameFoundNowhereSaysWhereItWasLookedFor) {
    TempDir dir;
    const auto path = dir.write("s.score.xml",
                                "<VibScore><Clef id=\"c\" href=\"erm-phone.clef.xml\"/><Bar "
                                "clef=\"c\"/></VibScore>");
    NamedClefs named;
    const auto diagnostic = first_diagnostic([&] { load_score_file(path, named.lookup()); });
    EXPECT_EQ(diagnostic.message,
              "clef \"c\": " + (dir.path() / "erm-phone.clef.xml").string() +
                  ": no such file beside the score, and no clef \"erm-phone\" in the test's "
                  "registry");
}

TEST(Bundle, MissingClefFileNamesTheDeclarationAndThePath) {
    TempDir dir;
    const auto path = dir.write("s.xml",
                                "<VibScore>\n  <Clef id=\"c\" href=\"nowhere.xml\"/>\n"
                                "<Bar clef=\"c\"/></VibScore>");
    const auto diagnostic = first_diagnostic([&] { load_score_file(path); });
    EXPECT_EQ(diagnostic.where.file, path.string());
    EXPECT_EQ(diagnostic.where.line, 2);
    EXPECT_EQ(diagnostic.where.column, 3);
    EXPECT_NE(diagnostic.message.find("nowhere.xml: cannot open: No such file"), std::string::npos)
        << diagnostic.message;
}

TEST(Bundle, InvalidClefFileIsReportedInTheClefFile) {
    TempDir dir;
    dir.write("c.xml", "<VibClef type=\"sine\">\n<Tempo>-1</Tempo></VibClef>");
    const auto path = dir.write("s.xml", one_clef_score("<Bar clef=\"c\"/>"));
    const auto diagnostic = first_diagnostic([&] { load_score_file(path); });
    EXPECT_EQ(diagnostic.where.file, (dir.path() / "c.xml").string());
    EXPECT_EQ(diagnostic.where.line, 2);
    EXPECT_NE(diagnostic.message.find("tempo \"-1\""), std::string::npos);
}

TEST(Bundle, ClefHrefToADirectoryIsRefused) {
    TempDir dir;
    dir.write("c.xml/inner", "");
    const auto path = dir.write("s.xml", one_clef_score("<Bar clef=\"c\"/>"));
    const auto diagnostic = first_diagnostic([&] { load_score_file(path); });
    EXPECT_NE(diagnostic.message.find("is a directory"), std::string::npos);
}

TEST(Bundle, StringBeyondTheBarsClefIsNamedAtTheNote) {
    const auto diagnostic = first_diagnostic([&] {
        bundle_from(one_clef_score("<Bar clef=\"c\">\n<Note length=\"8th\" number=\"1\" "
                                   "string=\"4\"/></Bar>"),
                    {{"c.xml", kClef}});
    });
    EXPECT_EQ(diagnostic.where.line, 2);
    EXPECT_NE(
        diagnostic.message.find("string 4 is beyond clef \"c\", which defines strings 1 to 3"),
        std::string::npos)
        << diagnostic.message;
}

TEST(Bundle, NumberBeyondTheBarsClefIsNamedAtTheNote) {
    const auto diagnostic = first_diagnostic([&] {
        bundle_from(one_clef_score("<Bar clef=\"c\">\n\n<Note length=\"8th\" number=\"3\" "
                                   "string=\"1\"/></Bar>"),
                    {{"c.xml", kClef}});
    });
    EXPECT_EQ(diagnostic.where.line, 3);
    EXPECT_NE(
        diagnostic.message.find("number 3 is beyond clef \"c\", which defines numbers 1 to 2"),
        std::string::npos);
}

TEST(Bundle, RefusesScoresLongerThanTheLimit) {
    std::string bars;
    // 60 s per whole note at tempo 15: 61 whole notes exceed one hour.
    for (int i = 0; i < 61; ++i) {
        bars += "<Bar clef=\"c\"><Rest length=\"whole\"/></Bar>";
    }
    const auto diagnostic = first_diagnostic([&] {
        bundle_from(one_clef_score(bars), {{"c.xml", sine_clef(15, {100}, {1})}});
    });
    EXPECT_NE(diagnostic.message.find("lasts 3660 s; the limit is 3600 s"), std::string::npos)
        << diagnostic.message;
}

TEST(Bundle, RefusesOversizedFilesBeforeParsing) {
    TempDir dir;
    const auto path = dir.write("big.xml", std::string(limits::document_bytes + 1, ' '));
    const auto diagnostic = first_diagnostic([&] { read_document_file(path); });
    EXPECT_EQ(diagnostic.where.file, path.string());
    EXPECT_NE(diagnostic.message.find("larger than the 1048576-byte limit"), std::string::npos);
}

TEST(Bundle, MissingScoreFileIsNamed) {
    const auto diagnostic = first_diagnostic([] { load_score_file("/nonexistent/s.xml"); });
    EXPECT_EQ(format(diagnostic), "/nonexistent/s.xml: cannot open: No such file or directory");
}

TEST(Bundle, TellsScoresFromClefsByRoot) {
    EXPECT_EQ(document_kind("<VibScore/>", "x"), DocumentKind::score);
    EXPECT_EQ(document_kind("<?xml version=\"1.0\"?><VibClef/>", "x"), DocumentKind::clef);
    const auto other = first_diagnostic([] { document_kind("\n<html/>", "page.xml"); });
    EXPECT_EQ(format(other),
              "page.xml:2:1: root element is <html>, expected <VibScore> or <VibClef>");
    const auto broken = first_diagnostic([] { document_kind("<VibScore>", "broken.xml"); });
    EXPECT_NE(broken.message.find("malformed XML"), std::string::npos);
}

TEST(DocumentKind, ParsesSingularAndPlural) {
    EXPECT_EQ(parse_document_kind("score"), DocumentKind::score);
    EXPECT_EQ(parse_document_kind("scores"), DocumentKind::score);
    EXPECT_EQ(parse_document_kind("clef"), DocumentKind::clef);
    EXPECT_EQ(parse_document_kind("clefs"), DocumentKind::clef);
    EXPECT_EQ(parse_document_kind("Score"), std::nullopt);
    EXPECT_EQ(parse_document_kind(""), std::nullopt);
    EXPECT_EQ(to_string(DocumentKind::score), "score");
    EXPECT_EQ(to_string(DocumentKind::clef), "clef");
}

}  // namespace
}  // namespace vibscore
