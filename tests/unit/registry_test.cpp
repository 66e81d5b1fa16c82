#include "daemon/registry/registry.hpp"

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <random>
#include <system_error>
#include <utility>

#include "score/limits.hpp"
#include "tests/support/pace.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using Code = RegistryError::Code;
using testing::file_names;
using testing::read_file;
using testing::sine_clef;
using testing::TempDir;

// 3 strings, 2 numbers.
const std::string kBaseClef = sine_clef(0.2, {100, 150, 200}, {0.5, 1.0});

// A one-note score on the given string of the clef at href. The <Clef> is at line 4, column 3.
std::string score_using(const std::string& href, int string = 1, const std::string& title = "t") {
    return "<?xml version=\"1.0\"?>\n<VibScore version=\"1.0\">\n  <Title>" + title +
           "</Title>\n  <Clef id=\"c\" href=\"" + href +
           "\"/>\n  <Bar clef=\"c\">\n    <Note length=\"quarter\" number=\"1\" string=\"" +
           std::to_string(string) + "\"/>\n  </Bar>\n</VibScore>\n";
}

std::vector<std::string> names_of(const std::vector<RegistryEntry>& entries) {
    std::vector<std::string> names;
    for (const auto& entry : entries) {
        names.push_back(entry.name);
    }
    return names;
}

// The message of the RegistryError f throws; fails the test unless it has the expected code.
template <typename F>
std::string error_of(Code expected, F&& f) {
    try {
        f();
    } catch (const RegistryError& error) {
        EXPECT_EQ(to_string(error.code()), to_string(expected)) << error.what();
        return error.what();
    }
    ADD_FAILURE() << "no RegistryError thrown";
    return {};
}

// Shipped: clef "base" and score "tune", which plays string 3 of base.
class RegistryTest : public ::testing::Test {
  protected:
    RegistryTest() {
        shipped_.write("base.clef.xml", kBaseClef);
        shipped_.write("tune.score.xml", score_using("base.clef.xml", 3, "Tune"));
    }

    std::filesystem::path store_dir() const { return store_.path() / "var" / "vibscore"; }
    Registry open(StoreLimits limits = {}) const {
        return Registry(shipped_.path(), store_dir(), limits);
    }

    TempDir shipped_;
    TempDir store_;
};

TEST_F(RegistryTest, LoadsShippedAndStoredDocuments) {
    std::filesystem::create_directories(store_dir());
    std::ofstream(store_dir() / "mine.clef.xml") << sine_clef(0.5, {80}, {1});
    std::ofstream(store_dir() / "song.score.xml") << score_using("mine.clef.xml", 1, "Song");
    std::ofstream(store_dir() / "notes.txt") << "not a document";
    const auto registry = open();
    EXPECT_THAT(registry.list(DocumentKind::clef),
                ElementsAre(RegistryEntry{"base", "sine, tempo 0.2 s, 3 strings", true},
                            RegistryEntry{"mine", "sine, tempo 0.5 s, 1 string", false}));
    EXPECT_THAT(
        registry.list(DocumentKind::score),
        ElementsAre(RegistryEntry{"song", "Song", false}, RegistryEntry{"tune", "Tune", true}));
    EXPECT_EQ(registry.stored_documents(), 2u);
    EXPECT_EQ(registry.score("song").clef_of(registry.score("song").score.bars[0]).tempo, 0.5);
}

TEST_F(RegistryTest, GetReturnsTheDocumentTextExactly) {
    const auto registry = open();
    EXPECT_EQ(registry.get(DocumentKind::clef, "base"), kBaseClef);
    EXPECT_EQ(registry.get(DocumentKind::score, "tune"), score_using("base.clef.xml", 3, "Tune"));
    EXPECT_THAT(error_of(Code::not_found, [&] { registry.get(DocumentKind::score, "base"); }),
                HasSubstr("score \"base\""));
    EXPECT_THAT(error_of(Code::not_found, [&] { registry.get(DocumentKind::clef, "nope"); }),
                HasSubstr("clef \"nope\""));
    error_of(Code::not_found, [&] { registry.score("nope"); });
    error_of(Code::not_found, [&] { registry.clef("nope"); });
}

TEST_F(RegistryTest, CreatesTheStoreDirectory) {
    open();
    struct stat status {};
    ASSERT_EQ(::stat(store_dir().c_str(), &status), 0);
    EXPECT_TRUE(S_ISDIR(status.st_mode));
    EXPECT_EQ(status.st_mode & 0777 & ~0755u, 0u);
}

TEST_F(RegistryTest, ComposesAScoreAndAClef) {
    auto registry = open();
    const auto clef_text = sine_clef(0.1, {60, 70}, {0.3});
    EXPECT_EQ(registry.compose("pulse", clef_text), DocumentKind::clef);
    const auto score_text = score_using("pulse.clef.xml", 2, "Beat");
    EXPECT_EQ(registry.compose("beat", score_text), DocumentKind::score);

    EXPECT_EQ(read_file(store_dir() / "pulse.clef.xml"), clef_text);
    EXPECT_EQ(read_file(store_dir() / "beat.score.xml"), score_text);
    EXPECT_EQ(registry.get(DocumentKind::score, "beat"), score_text);
    EXPECT_EQ(registry.clef("pulse").tempo, 0.1);
    const auto bundle = registry.score("beat");
    EXPECT_EQ(bundle.file, "score \"beat\"");
    EXPECT_EQ(bundle.clef_of(bundle.score.bars[0]).strings[1].frequency, 70.0);
    EXPECT_THAT(names_of(registry.list(DocumentKind::score)), ElementsAre("beat", "tune"));
    EXPECT_EQ(registry.stored_documents(), 2u);
    EXPECT_EQ(registry.stored_bytes(), clef_text.size() + score_text.size());
}

TEST_F(RegistryTest, AcceptsTheThreeHrefForms) {
    auto registry = open();
    for (const std::string href : {"base.clef.xml", "base.xml", "base"}) {
        EXPECT_EQ(registry.compose("s", score_using(href, 3)), DocumentKind::score) << href;
        EXPECT_EQ(registry.score("s").clefs.at("c").tempo, 0.2) << href;
    }
}

TEST_F(RegistryTest, ComposingAnExistingNameReplacesIt) {
    auto registry = open();
    registry.compose("s", score_using("base", 1, "First"));
    const auto second = score_using("base", 2, "Second");
    registry.compose("s", second);
    EXPECT_EQ(registry.get(DocumentKind::score, "s"), second);
    EXPECT_EQ(registry.list(DocumentKind::score).at(0).title, "Second");
    EXPECT_EQ(registry.stored_documents(), 1u);
    EXPECT_EQ(registry.stored_bytes(), second.size());
    EXPECT_EQ(file_names(store_dir()), std::vector<std::string>{"s.score.xml"});
}

TEST_F(RegistryTest, AScoreAndAClefMayShareAName) {
    auto registry = open();
    registry.compose("x", sine_clef(0.3, {90}, {1}));
    registry.compose("x", score_using("x.clef.xml"));
    EXPECT_TRUE(registry.contains(DocumentKind::clef, "x"));
    EXPECT_TRUE(registry.contains(DocumentKind::score, "x"));
    EXPECT_EQ(registry.score("x").clefs.at("c").tempo, 0.3);
}

TEST_F(RegistryTest, AStoredClefShadowsTheShippedOneUntilDeleted) {
    auto registry = open();
    const auto slower = sine_clef(0.4, {110, 160, 210}, {0.5, 1.0});
    registry.compose("base", slower);
    EXPECT_EQ(registry.get(DocumentKind::clef, "base"), slower);
    EXPECT_EQ(registry.origin(DocumentKind::clef, "base"), Origin::stored_over_shipped);
    EXPECT_THAT(registry.list(DocumentKind::clef),
                ElementsAre(RegistryEntry{"base", "sine, tempo 0.4 s, 3 strings", false}));
    // The shipped score now plays with the stored clef.
    EXPECT_EQ(registry.score("tune").clefs.at("c").tempo, 0.4);

    registry.remove(DocumentKind::clef, "base");
    EXPECT_EQ(registry.get(DocumentKind::clef, "base"), kBaseClef);
    EXPECT_EQ(registry.origin(DocumentKind::clef, "base"), Origin::shipped);
    EXPECT_EQ(registry.score("tune").clefs.at("c").tempo, 0.2);
    EXPECT_TRUE(file_names(store_dir()).empty());
}

TEST_F(RegistryTest, OriginTellsShippedStoredAndStoredOverShipped) {
    auto registry = open();
    EXPECT_EQ(registry.origin(DocumentKind::score, "tune"), Origin::shipped);
    registry.compose("mine", score_using("base", 1, "Mine"));
    EXPECT_EQ(registry.origin(DocumentKind::score, "mine"), Origin::stored);
    registry.compose("tune", score_using("base", 1, "My tune"));
    EXPECT_EQ(registry.origin(DocumentKind::score, "tune"), Origin::stored_over_shipped);
    EXPECT_EQ(to_string(Origin::stored_over_shipped), "stored-over-shipped");
    registry.remove(DocumentKind::score, "tune");
    EXPECT_EQ(registry.origin(DocumentKind::score, "tune"), Origin::shipped);
    try {
        (void)registry.origin(DocumentKind::score, "nothing");
        FAIL() << "no error";
    } catch (const RegistryError& error) {
        EXPECT_EQ(error.code(), RegistryError::Code::not_found);
        EXPECT_STREQ(error.what(), "no score \"nothing\"");
    }
    EXPECT_THROW((void)registry.origin(DocumentKind::score, "../x"), RegistryError);
}

TEST_F(RegistryTest, AStoredScoreShadowsTheShippedOneUntilDeleted) {
    auto registry = open();
    const auto mine = score_using("base", 1, "My tune");
    registry.compose("tune", mine);
    EXPECT_EQ(registry.get(DocumentKind::score, "tune"), mine);
    EXPECT_THAT(registry.list(DocumentKind::score),
                ElementsAre(RegistryEntry{"tune", "My tune", false}));
    registry.remove(DocumentKind::score, "tune");
    EXPECT_THAT(registry.list(DocumentKind::score),
                ElementsAre(RegistryEntry{"tune", "Tune", true}));
    EXPECT_EQ(registry.score("tune").score.title, "Tune");
}

TEST_F(RegistryTest, RefusesBadNamesNamingThem) {
    auto registry = open();
    const std::string too_long(65, 'a');
    for (const std::string& name : std::vector<std::string>{
             "", "A", "Tune", "a/b", "/etc/passwd", "..", ".", ".hidden", "-a", "_a", "a b", "a\\b",
             "tune.SCORE", "é", std::string("a\0b", 3), too_long}) {
        const auto message =
            error_of(Code::invalid_document, [&] { registry.compose(name, score_using("base")); });
        const auto shown = name.find('\0') == std::string::npos ? name.substr(0, 80) : "a\\x00b";
        EXPECT_THAT(message, HasSubstr("invalid name \"" + shown + "\"")) << name;
        error_of(Code::invalid_document, [&] { registry.get(DocumentKind::score, name); });
        error_of(Code::invalid_document, [&] { registry.remove(DocumentKind::clef, name); });
    }
    EXPECT_EQ(registry.stored_documents(), 0u);
    EXPECT_TRUE(file_names(store_dir()).empty());
}

TEST_F(RegistryTest, AcceptsGoodNames) {
    auto registry = open();
    for (const std::string& name :
         std::vector<std::string>{"a", "0", "a.b-c_d", "9lives", std::string(64, 'z')}) {
        EXPECT_TRUE(is_valid_name(name)) << name;
        registry.compose(name, score_using("base"));
        EXPECT_TRUE(registry.contains(DocumentKind::score, name)) << name;
    }
}

TEST_F(RegistryTest, RefusesClefHrefsThatAreNotBareNames) {
    // A clef where a path would lead, to show that no path is ever followed.
    std::ofstream(store_.path() / "evil.clef.xml") << kBaseClef;
    auto registry = open();
    for (const std::string href :
         {"../evil.clef.xml", "../../evil.clef.xml", "/etc/passwd", "sub/base.clef.xml",
          "./base.clef.xml", "..", "..clef.xml", "Base.clef.xml", "base.clef.xml/"}) {
        const auto message =
            error_of(Code::invalid_document, [&] { registry.compose("s", score_using(href)); });
        EXPECT_THAT(message, HasSubstr("score \"s\":4:3: clef \"c\": href \"" + href + "\""))
            << message;
        error_of(Code::invalid_document, [&] { registry.inline_score(score_using(href)); });
    }
    EXPECT_FALSE(registry.contains(DocumentKind::score, "s"));
}

TEST_F(RegistryTest, RefusesAScoreNamingAnUnknownClef) {
    auto registry = open();
    const auto message =
        error_of(Code::invalid_document, [&] { registry.compose("s", score_using("ghost")); });
    EXPECT_THAT(message, HasSubstr("score \"s\":4:3: clef \"c\": no clef named \"ghost\""));
}

TEST_F(RegistryTest, InvalidDocumentMessagesGiveLineAndColumn) {
    auto registry = open();
    auto bad = score_using("base");
    bad.replace(bad.find("quarter"), 7, "9th");
    EXPECT_THAT(error_of(Code::invalid_document, [&] { registry.compose("s", bad); }),
                HasSubstr("score \"s\":6:5: unknown length \"9th\""));
    EXPECT_THAT(
        error_of(Code::invalid_document, [&] { registry.compose("s", score_using("base", 4)); }),
        HasSubstr("score \"s\":6:5: string 4 is beyond clef \"c\""));
    EXPECT_THAT(error_of(Code::invalid_document,
                         [&] { registry.compose("k", "<VibClef type=\"sine\">\n<Tempo>-1"); }),
                HasSubstr("\"k\":2:"));
    EXPECT_THAT(error_of(Code::invalid_document, [&] { registry.compose("k", "<Other/>"); }),
                HasSubstr("<Other>"));
    EXPECT_EQ(registry.stored_documents(), 0u);
}

TEST_F(RegistryTest, RefusesDocumentsOverTheSizeLimit) {
    auto registry = open();
    const std::string huge(limits::document_bytes + 1, ' ');
    EXPECT_THAT(error_of(Code::limit_exceeded, [&] { registry.compose("big", huge); }),
                HasSubstr("\"big\""));
    error_of(Code::limit_exceeded, [&] { registry.inline_score(huge); });
    auto small = open({.document_bytes = 100});
    error_of(Code::limit_exceeded, [&] { small.compose("s", score_using("base")); });
}

TEST_F(RegistryTest, RefusesMoreDocumentsThanTheStoreLimit) {
    auto registry = open({.documents = 3});
    registry.compose("a", score_using("base"));
    registry.compose("b", score_using("base"));
    registry.compose("c", sine_clef(1, {1}, {1}));
    EXPECT_THAT(error_of(Code::limit_exceeded, [&] { registry.compose("d", score_using("base")); }),
                HasSubstr("score \"d\""));
    registry.compose("a", score_using("base", 2));  // replacing needs no new room
    registry.remove(DocumentKind::score, "b");
    registry.compose("d", score_using("base"));
    EXPECT_EQ(registry.stored_documents(), 3u);
}

TEST_F(RegistryTest, RefusesMoreBytesThanTheStoreLimit) {
    const auto text = score_using("base");
    auto registry = open({.total_bytes = 2 * text.size() + 10});
    registry.compose("a", text);
    registry.compose("b", text);
    error_of(Code::limit_exceeded, [&] { registry.compose("c", text); });
    error_of(Code::limit_exceeded, [&] { registry.compose("a", text + std::string(20, ' ')); });
    registry.compose("a", text + std::string(10, ' '));
    EXPECT_EQ(registry.stored_bytes(), 2 * text.size() + 10);
}

TEST_F(RegistryTest, DeleteRefusesMissingAndShippedDocuments) {
    auto registry = open();
    EXPECT_THAT(error_of(Code::not_found, [&] { registry.remove(DocumentKind::score, "nope"); }),
                HasSubstr("score \"nope\""));
    error_of(Code::not_found, [&] { registry.remove(DocumentKind::clef, "tune"); });
    EXPECT_THAT(
        error_of(Code::permission_denied, [&] { registry.remove(DocumentKind::clef, "base"); }),
        HasSubstr("shipped documents are read-only"));
    error_of(Code::permission_denied, [&] { registry.remove(DocumentKind::score, "tune"); });
}

TEST_F(RegistryTest, DeleteRefusesAClefThatScoresUse) {
    auto registry = open();
    registry.compose("mine", sine_clef(0.5, {80}, {1}));
    registry.compose("song", score_using("mine"));
    registry.compose("other", score_using("mine.xml"));
    const auto message =
        error_of(Code::in_use, [&] { registry.remove(DocumentKind::clef, "mine"); });
    EXPECT_THAT(message, HasSubstr("score \"other\""));
    EXPECT_THAT(message, HasSubstr("score \"song\""));
    EXPECT_TRUE(registry.contains(DocumentKind::clef, "mine"));
    registry.remove(DocumentKind::score, "song");
    registry.remove(DocumentKind::score, "other");
    registry.remove(DocumentKind::clef, "mine");
    EXPECT_TRUE(file_names(store_dir()).empty());
}

TEST_F(RegistryTest, DeleteRefusesAShadowingClefWhenTheShippedOneWouldNotFit) {
    auto registry = open();
    registry.compose("base", sine_clef(0.2, {1, 2, 3, 4}, {1, 1}));
    registry.compose("wide", score_using("base", 4));
    const auto message =
        error_of(Code::in_use, [&] { registry.remove(DocumentKind::clef, "base"); });
    EXPECT_THAT(message, HasSubstr("score \"wide\""));
    EXPECT_THAT(message, HasSubstr("string 4 is beyond"));
    EXPECT_TRUE(std::filesystem::exists(store_dir() / "base.clef.xml"));
}

TEST_F(RegistryTest, RefusesAClefChangeThatBreaksAScoreUsingIt) {
    auto registry = open();
    const auto three = sine_clef(0.5, {80, 90, 100}, {1});
    registry.compose("mine", three);
    registry.compose("song", score_using("mine", 3));
    const auto message = error_of(Code::invalid_document, [&] {
        registry.compose("mine", sine_clef(0.5, {80, 90}, {1}));
    });
    EXPECT_THAT(message, HasSubstr("score \"song\""));
    EXPECT_THAT(message, HasSubstr("score \"song\":6:5: string 3 is beyond clef \"c\""));
    EXPECT_EQ(registry.get(DocumentKind::clef, "mine"), three);
    EXPECT_EQ(read_file(store_dir() / "mine.clef.xml"), three);
    EXPECT_EQ(registry.score("song").clefs.at("c").strings.size(), 3u);

    // The shipped score counts too, even where a stored score shadows it.
    registry.compose("tune", score_using("base", 1));
    EXPECT_THAT(error_of(Code::invalid_document,
                         [&] {
                             registry.compose("base", sine_clef(0.2, {1, 2}, {1, 1}));
                         }),
                HasSubstr("shipped score \"tune\""));
}

TEST_F(RegistryTest, AClefChangeThatFitsReachesTheScoresUsingIt) {
    auto registry = open();
    registry.compose("mine", sine_clef(0.5, {80, 90, 100}, {1}));
    registry.compose("song", score_using("mine", 3));
    registry.compose("mine", sine_clef(0.25, {80, 90, 120}, {1}));
    const auto bundle = registry.score("song");
    EXPECT_EQ(bundle.clefs.at("c").tempo, 0.25);
    EXPECT_EQ(bundle.clefs.at("c").strings[2].frequency, 120.0);
}

TEST_F(RegistryTest, PersistsAcrossInstances) {
    const auto clef_text = sine_clef(0.5, {80}, {1});
    const auto song = score_using("mine", 1, "Song");
    {
        auto registry = open();
        registry.compose("mine", clef_text);
        registry.compose("song", song);
        registry.compose("gone", score_using("base"));
        registry.compose("base", sine_clef(0.3, {1, 2, 3}, {1, 1}));
        registry.remove(DocumentKind::score, "gone");
    }
    const auto registry = open();
    EXPECT_EQ(registry.get(DocumentKind::clef, "mine"), clef_text);
    EXPECT_EQ(registry.get(DocumentKind::score, "song"), song);
    EXPECT_FALSE(registry.contains(DocumentKind::score, "gone"));
    EXPECT_EQ(registry.score("tune").clefs.at("c").tempo, 0.3);
    EXPECT_EQ(registry.stored_documents(), 3u);
    EXPECT_THAT(names_of(registry.list(DocumentKind::score)), ElementsAre("song", "tune"));
}

TEST_F(RegistryTest, RemovesStaleTemporaryFilesAtStart) {
    std::filesystem::create_directories(store_dir());
    std::ofstream(store_dir() / ".song.score.xml.tmp-a1B2c3") << "<VibScore><Ti";
    std::ofstream(store_dir() / "song.score.xml") << score_using("base");
    const auto registry = open();
    EXPECT_EQ(file_names(store_dir()), std::vector<std::string>{"song.score.xml"});
    EXPECT_THAT(names_of(registry.list(DocumentKind::score)), ElementsAre("song", "tune"));
}

TEST_F(RegistryTest, SkipsBadStoredFilesAndLoadsTheOthers) {
    std::filesystem::create_directories(store_dir());
    std::ofstream(store_dir() / "good.score.xml") << score_using("base");
    std::ofstream(store_dir() / "cut.score.xml") << score_using("base").substr(0, 90);
    std::ofstream(store_dir() / "broken.clef.xml")
        << "<VibClef type=\"sine\">\n<Tempo>-1</Tempo></VibClef>";
    std::ofstream(store_dir() / "orphan.score.xml") << score_using("broken");
    std::ofstream(store_dir() / "wrong.clef.xml") << score_using("base");
    std::ofstream(store_dir() / "Upper.score.xml") << score_using("base");
    std::filesystem::create_directories(store_dir() / "dir.score.xml");

    ::testing::internal::CaptureStderr();
    const auto registry = open();
    const auto log = ::testing::internal::GetCapturedStderr();

    EXPECT_THAT(names_of(registry.list(DocumentKind::score)), ElementsAre("good", "tune"));
    EXPECT_THAT(names_of(registry.list(DocumentKind::clef)), ElementsAre("base"));
    EXPECT_EQ(registry.stored_documents(), 1u);
    for (const auto* file : {"cut.score.xml", "broken.clef.xml", "orphan.score.xml",
                             "wrong.clef.xml", "Upper.score.xml", "dir.score.xml"}) {
        EXPECT_THAT(log, HasSubstr((store_dir() / file).string())) << log;
    }
    EXPECT_THAT(log, HasSubstr("<4>"));
    EXPECT_THAT(log, HasSubstr("clef \"broken\":2:1: tempo \"-1\""));
    EXPECT_THAT(log, HasSubstr("no clef named \"broken\""));
    EXPECT_THAT(log, Not(HasSubstr("good.score.xml")));
}

TEST_F(RegistryTest, AMissingShippedDirectoryIsOnlyAWarning) {
    ::testing::internal::CaptureStderr();
    Registry registry(shipped_.path() / "missing", store_dir());
    EXPECT_THAT(::testing::internal::GetCapturedStderr(),
                HasSubstr((shipped_.path() / "missing").string()));
    EXPECT_TRUE(registry.list(DocumentKind::score).empty());
    registry.compose("k", kBaseClef);
    EXPECT_THAT(names_of(registry.list(DocumentKind::clef)), ElementsAre("k"));
}

TEST_F(RegistryTest, AFailedWriteChangesNothingAndNamesThePath) {
    auto registry = open();
    registry.compose("s", score_using("base", 1));
    std::filesystem::remove_all(store_dir());
    try {
        registry.compose("s", score_using("base", 2));
        FAIL() << "no error";
    } catch (const std::system_error& error) {
        EXPECT_THAT(error.what(), HasSubstr((store_dir() / "s.score.xml").string()));
        EXPECT_THAT(error.what(), HasSubstr("No such file or directory"));
    }
    EXPECT_EQ(registry.get(DocumentKind::score, "s"), score_using("base", 1));
}

TEST_F(RegistryTest, InlineScoresUseRegistryClefs) {
    const auto registry = open();
    const auto bundle = registry.inline_score(score_using("base.clef.xml", 3));
    EXPECT_EQ(bundle.file, "<inline score>");
    EXPECT_EQ(bundle.clefs.at("c").strings[2].frequency, 200.0);
    EXPECT_THAT(
        error_of(Code::invalid_document, [&] { registry.inline_score(score_using("ghost")); }),
        HasSubstr("<inline score>:4:3: clef \"c\": no clef named \"ghost\""));
    EXPECT_THAT(error_of(Code::invalid_document, [&] { registry.inline_score(kBaseClef); }),
                HasSubstr("expected <VibScore>"));
}

TEST_F(RegistryTest, APreparedComposeWritesNothingUntilCommitted) {
    auto registry = open();
    const auto score_text = score_using("base.clef.xml", 2, "Beat");
    auto prepared = registry.prepare_compose("beat", score_text);
    EXPECT_EQ(prepared.kind(), DocumentKind::score);
    EXPECT_EQ(prepared.name(), "beat");
    EXPECT_FALSE(registry.contains(DocumentKind::score, "beat"));
    EXPECT_FALSE(std::filesystem::exists(store_dir() / "beat.score.xml"));

    const auto generation = registry.generation();
    EXPECT_EQ(registry.commit_compose(std::move(prepared)), DocumentKind::score);
    EXPECT_EQ(registry.generation(), generation + 1);
    EXPECT_EQ(read_file(store_dir() / "beat.score.xml"), score_text);
    EXPECT_EQ(registry.get(DocumentKind::score, "beat"), score_text);
}

TEST_F(RegistryTest, PrepareRefusesAsComposeDoes) {
    const auto registry = open(StoreLimits{200, 1000, 1u << 20});
    EXPECT_THAT(error_of(Code::invalid_document,
                         [&] { registry.prepare_compose("beat", score_using("ghost")); }),
                HasSubstr("no clef named \"ghost\""));
    EXPECT_THAT(error_of(Code::limit_exceeded,
                         [&] { registry.prepare_compose("big", std::string(201, ' ')); }),
                HasSubstr("is 201 bytes; the limit is 200"));
    EXPECT_EQ(registry.generation(), 0u);
}

// What a prepared compose was checked against may be gone by its commit: here the clef its score
// uses is deleted in between, and storing it would break the registry's invariant.
TEST_F(RegistryTest, APreparedComposeIsNotCommittedAfterAnotherChange) {
    auto registry = open();
    ASSERT_EQ(registry.compose("mine", sine_clef(0.5, {80}, {1})), DocumentKind::clef);
    auto prepared = registry.prepare_compose("song", score_using("mine.clef.xml", 1));
    registry.remove(DocumentKind::clef, "mine");
    EXPECT_EQ(registry.commit_compose(std::move(prepared)), std::nullopt);
    EXPECT_FALSE(registry.contains(DocumentKind::score, "song"));
    EXPECT_FALSE(std::filesystem::exists(store_dir() / "song.score.xml"));

    auto after_compose = registry.prepare_compose("song", score_using("base.clef.xml", 1));
    ASSERT_EQ(registry.compose("other", score_using("base.clef.xml", 2)), DocumentKind::score);
    EXPECT_EQ(registry.commit_compose(std::move(after_compose)), std::nullopt);
    EXPECT_FALSE(registry.contains(DocumentKind::score, "song"));
}

TEST(Registry, LoadsEveryShippedDocument) {
    const std::filesystem::path shipped = testing::required_env("VIBSCORE_CLEFS");
    TempDir store;
    ::testing::internal::CaptureStderr();
    const Registry registry(shipped, store.path());
    const auto log = ::testing::internal::GetCapturedStderr();
    EXPECT_THAT(log, Not(HasSubstr("skipping"))) << log;
    std::size_t scores = 0;
    std::size_t clefs = 0;
    for (const auto& entry : std::filesystem::directory_iterator(shipped)) {
        const auto name = entry.path().filename().string();
        scores += name.ends_with(".score.xml") ? 1 : 0;
        clefs += name.ends_with(".clef.xml") ? 1 : 0;
    }
    EXPECT_EQ(registry.list(DocumentKind::score).size(), scores);
    EXPECT_EQ(registry.list(DocumentKind::clef).size(), clefs);
    EXPECT_EQ(registry.score("alarm").file, "score \"alarm\"");
    EXPECT_EQ(registry.stored_documents(), 0u);
}

// Crash safety: a child composes in a loop and is killed with SIGKILL at a random moment.

// Owns a descriptor of the crash test's pipes.
class Fd {
  public:
    explicit Fd(int fd) : fd_(fd) {}
    ~Fd() { reset(); }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    int get() const { return fd_; }
    void reset() {
        if (fd_ >= 0) {
            ::close(std::exchange(fd_, -1));
        }
    }

  private:
    int fd_;
};

constexpr long kCrashNames = 4;  // name 0 is a clef; names 1-3 are scores that use it

std::string crash_name(long seq) {
    return seq % kCrashNames == 0 ? "crash-clef" : "crash-" + std::to_string(seq % kCrashNames);
}

// A distinct, complete document for each sequence number, marked at both ends. At about 60 KB
// the kill often lands while it is being written.
std::string crash_document(long seq) {
    const auto mark = "<!-- seq " + std::to_string(seq) + " -->\n";
    if (seq % kCrashNames == 0) {
        const double tempo = 0.1 + static_cast<double>(seq % 100) / 1000;
        return mark + sine_clef(tempo, {100, 150, 200}, {0.5, 1.0}) + "\n<!-- " +
               std::string(60'000, 'p') + " -->\n" + mark;
    }
    std::string text = mark + "<VibScore version=\"1.0\">\n  <Title>" + crash_name(seq) + " seq " +
                       std::to_string(seq) +
                       "</Title>\n  <Clef id=\"c\" href=\"crash-clef.clef.xml\"/>\n";
    for (int bar = 0; bar < 600; ++bar) {
        text += "  <Bar clef=\"c\"><Note length=\"16th\" number=\"2\" string=\"" +
                std::to_string(1 + bar % 3) + "\"/><Rest length=\"16th\"/></Bar>\n";
    }
    return text + "</VibScore>\n" + mark;
}

// The sequence number a stored document was composed with, or -1. (Not std::regex: GCC 12
// warns inside it under the sanitizers.)
long crash_seq(const std::string& text) {
    constexpr std::string_view prefix = "<!-- seq ";
    if (!text.starts_with(prefix)) {
        return -1;
    }
    const auto digits_end = text.find_first_not_of("0123456789", prefix.size());
    if (digits_end == prefix.size() || digits_end == std::string::npos ||
        text.compare(digits_end, 5, " -->\n") != 0) {
        return -1;
    }
    return std::stol(text.substr(prefix.size(), digits_end - prefix.size()));
}

// The child: composes forever, acknowledging each compose on ack_fd once it has returned.
[[noreturn]] void compose_until_killed(const TempDir& shipped, const TempDir& store, long first,
                                       int ack_fd) {
    // Keep the registry's per-compose log lines out of the test log, but not an error.
    const Fd error_fd(::dup(STDERR_FILENO));
    const Fd null_fd(::open("/dev/null", O_WRONLY | O_CLOEXEC));
    ::dup2(null_fd.get(), STDERR_FILENO);
    int status = 0;
    try {
        Registry registry(shipped.path(), store.path());
        for (long seq = first; seq < first + 1'000'000; ++seq) {
            registry.compose(crash_name(seq), crash_document(seq));
            if (::write(ack_fd, &seq, sizeof seq) != sizeof seq) {
                status = 3;
                break;
            }
        }
    } catch (const std::exception& error) {
        const auto message = std::string("crash child: ") + error.what() + "\n";
        [[maybe_unused]] const auto written =
            ::write(error_fd.get(), message.data(), message.size());
        status = 2;
    }
    // No destructors, no atexit handlers: the parent's TempDirs are not the child's to remove.
    ::_exit(status);
}

bool read_seq(int fd, long& seq) {
    ssize_t got = 0;
    do {
        got = ::read(fd, &seq, sizeof seq);
    } while (got < 0 && errno == EINTR);
    return got == sizeof seq;  // writes of a long to a pipe are atomic
}

TEST(RegistryCrash, SigkillNeverLeavesAPartialDocumentNorLosesAnAcknowledgedOne) {
    const TempDir shipped;
    const TempDir store;
    std::mt19937 random(std::random_device{}());
    std::map<std::string, long> durable;  // name -> the seq known to be stored
    int interrupted_writes = 0;
    int acknowledged = 0;
    for (long round = 0; round < 40; ++round) {
        int fds[2];
        ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
        Fd read_end(fds[0]);
        Fd write_end(fds[1]);
        const long first = round * 1'000'000;  // a multiple of kCrashNames: the clef comes first
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            read_end.reset();
            compose_until_killed(shipped, store, first, write_end.get());
        }
        write_end.reset();

        long last = first - 1;
        long seq = 0;
        const auto record = [&](long acked) {
            durable[crash_name(acked)] = acked;
            last = acked;
            ++acknowledged;
        };
        for (int wanted = std::uniform_int_distribution(1, 6)(random);
             wanted > 0 && read_seq(read_end.get(), seq); --wanted) {
            record(seq);
        }
        // A random 0-2 ms more of writing, so that the kill lands anywhere in a write: the
        // time is the test's subject (where the crash falls), not a wait for anything.
        vibscore::testing::pace_for(
            std::chrono::microseconds(std::uniform_int_distribution(0, 2000)(random)));
        ::kill(child, SIGKILL);
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        while (read_seq(read_end.get(), seq)) {
            record(seq);  // acknowledged before the kill
        }
        ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
            << "the child stopped by itself, status " << status;
        const long in_flight = last + 1;

        for (const auto& name : file_names(store.path())) {
            interrupted_writes += name.starts_with(".") ? 1 : 0;
        }
        ::testing::internal::CaptureStderr();
        const Registry registry(shipped.path(), store.path());
        const auto log = ::testing::internal::GetCapturedStderr();
        EXPECT_THAT(log, Not(HasSubstr("skipping"))) << log;

        // Every file left is a complete document: none was skipped and each is byte-exact.
        std::size_t documents = 0;
        for (const auto& file : file_names(store.path())) {
            ASSERT_FALSE(file.starts_with(".")) << file << " survived the restart";
            const auto text = read_file(store.path() / file);
            const long stored = crash_seq(text);
            ASSERT_GE(stored, 0) << file << " starts with " << text.substr(0, 40);
            EXPECT_EQ(text, crash_document(stored)) << file << " is not seq " << stored;
            EXPECT_TRUE(file.starts_with(crash_name(stored) + ".")) << file;
            ++documents;
        }
        EXPECT_EQ(registry.stored_documents(), documents);

        // Every acknowledged compose is there, or the one in flight that replaced it.
        for (auto& [name, expected] : durable) {
            const auto kind = name == "crash-clef" ? DocumentKind::clef : DocumentKind::score;
            ASSERT_TRUE(registry.contains(kind, name)) << name;
            const auto text = registry.get(kind, name);
            const long stored = crash_seq(text);
            EXPECT_TRUE(stored == expected || stored == in_flight)
                << name << ": stored seq " << stored << ", acknowledged " << expected
                << ", in flight " << in_flight;
            EXPECT_EQ(text, crash_document(stored));
            expected = stored;
        }
        if (crash_name(in_flight) != "crash-clef" && !durable.contains(crash_name(in_flight)) &&
            registry.contains(DocumentKind::score, crash_name(in_flight))) {
            durable[crash_name(in_flight)] = in_flight;  // created but not acknowledged
        }
    }
    EXPECT_GT(acknowledged, 0);
    RecordProperty("acknowledged_composes", acknowledged);
    RecordProperty("interrupted_writes", interrupted_writes);
    std::cout << "crash test: " << acknowledged << " acknowledged composes, " << interrupted_writes
              << " writes interrupted by SIGKILL\n";
}

}  // namespace
}  // namespace vibscore::daemon
