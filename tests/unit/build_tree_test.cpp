// A program run from its build tree finds its checkout's files: meson's own record of the
// source folder (meson-info/meson-info.json), never a path compiled in.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "config.h"
#include "daemon/command_line.hpp"
#include "json/build_tree.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

namespace fs = std::filesystem;

class BuildTree : public ::testing::Test {
  protected:
    // TREE/build/meson-info/meson-info.json holding `info`; returns TREE/build.
    fs::path build_with_info(const std::string& info) const {
        const auto build = dir.path() / "build";
        fs::create_directories(build / "meson-info");
        fs::create_directories(build / "daemon");
        std::ofstream(build / "meson-info" / "meson-info.json") << info;
        return build;
    }
    testing::TempDir dir;
};

TEST_F(BuildTree, AProgramInABuildTreeHasTheSourceMesonInfoNames) {
    const auto build = build_with_info(
        R"({"directories": {"source": "/src/vibscore", "build": "/src/vibscore/build"}})");
    EXPECT_EQ(source_tree_of(build / "daemon" / "vibscored"), fs::path("/src/vibscore"));
    // Any depth below the build folder: build/tests/unit/NAME_test too.
    EXPECT_EQ(source_tree_of(build / "a" / "b" / "c" / "program"), fs::path("/src/vibscore"));
}

TEST_F(BuildTree, AProgramInNoBuildTreeHasNone) {
    fs::create_directories(dir.path() / "usr" / "sbin");
    EXPECT_EQ(source_tree_of(dir.path() / "usr" / "sbin" / "vibscored"), std::nullopt);
    EXPECT_EQ(source_tree_of("/usr/sbin/vibscored"), std::nullopt);
    EXPECT_EQ(source_tree_of("vibscored"), std::nullopt);
}

TEST_F(BuildTree, AMesonInfoThatNamesNoSourceIsNoBuildTree) {
    for (const char* info :
         {"", "not json", "[]", R"({"directories": {}})", R"({"directories": {"source": 3}})",
          R"({"directories": {"source": ""}})"}) {
        const auto build = build_with_info(info);
        EXPECT_EQ(source_tree_of(build / "daemon" / "vibscored"), std::nullopt) << info;
    }
}

// Each item of the data locator, installed and in a build tree, decided on its own.
class DataLocator : public BuildTree {
  protected:
    // TREE/build, a build tree of the source folder TREE/src (made, empty).
    fs::path build_of_source() const {
        fs::create_directories(source());
        return build_with_info(R"({"directories": {"source": ")" + source().string() + R"("}})");
    }
    fs::path source() const { return dir.path() / "src"; }
    void add_clefs() const { fs::create_directories(source() / "clefs"); }
    void add_theme() const {
        fs::create_directories(source() / "feedback" / "themes");
        std::ofstream(source() / "feedback" / "themes" / "default.json") << "{}";
    }
    void add_docs() const { fs::create_directories(source() / "docs"); }
};

TEST_F(DataLocator, InstalledDataIsWhatConfigHNames) {
    const auto installed = installed_data();
    EXPECT_EQ(installed.clefs, fs::path(VIBSCORE_CLEFDIR));
    EXPECT_EQ(installed.feedback_theme, fs::path(VIBSCORE_FEEDBACK_THEME));
    EXPECT_EQ(installed.docs, fs::path(VIBSCORE_CLIENT_DOCDIR));
}

TEST_F(DataLocator, AProgramInNoBuildTreeGetsEveryItemInstalled) {
    fs::create_directories(dir.path() / "usr" / "bin");
    const auto found = data_locations_of(dir.path() / "usr" / "bin" / "vibscore");
    EXPECT_EQ(found.clefs, fs::path(VIBSCORE_CLEFDIR));
    EXPECT_EQ(found.feedback_theme, fs::path(VIBSCORE_FEEDBACK_THEME));
    EXPECT_EQ(found.docs, fs::path(VIBSCORE_CLIENT_DOCDIR));
}

TEST_F(DataLocator, AProgramInABuildTreeGetsItsCheckoutsClefsThemeAndDocs) {
    const auto build = build_of_source();
    add_clefs();
    add_theme();
    add_docs();
    const auto found = data_locations_of(build / "client" / "vibscore");
    EXPECT_EQ(found.clefs, source() / "clefs");
    EXPECT_EQ(found.feedback_theme, source() / "feedback" / "themes" / "default.json");
    EXPECT_EQ(found.docs, source() / "docs");
}

TEST_F(DataLocator, AnItemTheCheckoutLacksIsTheInstalledOneTheOthersStayTheCheckouts) {
    const auto build = build_of_source();
    const auto program = build / "feedback" / "vibscore-feedback";
    EXPECT_EQ(data_locations_of(program).clefs, fs::path(VIBSCORE_CLEFDIR));
    EXPECT_EQ(data_locations_of(program).feedback_theme, fs::path(VIBSCORE_FEEDBACK_THEME));
    EXPECT_EQ(data_locations_of(program).docs, fs::path(VIBSCORE_CLIENT_DOCDIR));

    add_theme();  // the theme only
    auto found = data_locations_of(program);
    EXPECT_EQ(found.clefs, fs::path(VIBSCORE_CLEFDIR));
    EXPECT_EQ(found.feedback_theme, source() / "feedback" / "themes" / "default.json");
    EXPECT_EQ(found.docs, fs::path(VIBSCORE_CLIENT_DOCDIR));

    add_clefs();  // and the clefs
    found = data_locations_of(program);
    EXPECT_EQ(found.clefs, source() / "clefs");
    EXPECT_EQ(found.docs, fs::path(VIBSCORE_CLIENT_DOCDIR));
}

TEST_F(DataLocator, AFileWhereAFolderBelongsOrAFolderWhereTheThemeBelongsIsNotTaken) {
    const auto build = build_of_source();
    std::ofstream(source() / "clefs") << "not a folder";
    std::ofstream(source() / "docs") << "not a folder";
    fs::create_directories(source() / "feedback" / "themes" / "default.json");
    const auto found = data_locations_of(build / "client" / "vibscore");
    EXPECT_EQ(found.clefs, fs::path(VIBSCORE_CLEFDIR));
    EXPECT_EQ(found.feedback_theme, fs::path(VIBSCORE_FEEDBACK_THEME));
    EXPECT_EQ(found.docs, fs::path(VIBSCORE_CLIENT_DOCDIR));
}

TEST_F(DataLocator, ABuildTreeWhoseMesonInfoNamesNoSourceGetsEveryItemInstalled) {
    add_clefs();
    add_theme();
    add_docs();
    const auto build = build_with_info(R"({"directories": {"source": ""}})");
    const auto found = data_locations_of(build / "client" / "vibscore");
    EXPECT_EQ(found.clefs, fs::path(VIBSCORE_CLEFDIR));
    EXPECT_EQ(found.feedback_theme, fs::path(VIBSCORE_FEEDBACK_THEME));
    EXPECT_EQ(found.docs, fs::path(VIBSCORE_CLIENT_DOCDIR));
}

// $FEEDBACK_THEME for the test's span, put back after.
class FeedbackThemeVariable {
  public:
    explicit FeedbackThemeVariable(const char* value) {
        if (const char* before = std::getenv("FEEDBACK_THEME")) {
            before_ = before;
        }
        ::setenv("FEEDBACK_THEME", value, 1);
    }
    ~FeedbackThemeVariable() {
        if (before_) {
            ::setenv("FEEDBACK_THEME", before_->c_str(), 1);
        } else {
            ::unsetenv("FEEDBACK_THEME");
        }
    }
    FeedbackThemeVariable(const FeedbackThemeVariable&) = delete;
    FeedbackThemeVariable& operator=(const FeedbackThemeVariable&) = delete;

  private:
    std::optional<std::string> before_;
};

TEST(DefaultFeedbackTheme, IsFeedbackThemeWhenSetEvenToAFileThatIsNotThere) {
    const FeedbackThemeVariable set("/nonexistent/theme.json");
    EXPECT_EQ(default_feedback_theme(data_locations()), fs::path("/nonexistent/theme.json"));
    EXPECT_EQ(default_feedback_theme(installed_data()), fs::path("/nonexistent/theme.json"));
}

TEST(DefaultFeedbackTheme, IsTheLocatedThemeWhenFeedbackThemeIsEmpty) {
    const FeedbackThemeVariable empty("");
    EXPECT_EQ(default_feedback_theme(data_locations()), data_locations().feedback_theme);
    EXPECT_EQ(default_feedback_theme(installed_data()), fs::path(VIBSCORE_FEEDBACK_THEME));
}

// This test program lies in the build tree of the checkout whose files the tests use.
TEST(DataLocations, OfAProgramInItsBuildTreeAreItsCheckoutsThemeAndDocs) {
    const auto found = data_locations();
    const fs::path checkout_theme = std::getenv("VIBSCORE_FEEDBACK_THEME");
    EXPECT_TRUE(fs::equivalent(found.feedback_theme, checkout_theme))
        << found.feedback_theme << " is not " << checkout_theme;
    EXPECT_TRUE(fs::equivalent(found.docs, checkout_theme.parent_path() / ".." / ".." / "docs"))
        << found.docs;
}

// This test program lies in the build tree of the checkout whose clefs/ the tests use.
TEST(ShippedClefsFolder, OfAProgramInItsBuildTreeIsItsCheckoutsClefs) {
    const fs::path checkout_clefs = std::getenv("VIBSCORE_CLEFS");
    EXPECT_TRUE(fs::equivalent(shipped_clefs_folder(), checkout_clefs))
        << shipped_clefs_folder() << " is not " << checkout_clefs;
    EXPECT_NE(shipped_clefs_folder(), fs::path(VIBSCORE_CLEFDIR));
}

TEST(ShippedClefsFolder, IsWhereVibscoredFromTheBuildTreeLooksWithoutShippedConfigured) {
    testing::TempDir dir;
    daemon::CommandLine command_line;
    command_line.config = (dir.path() / "absent.conf").string();  // defaults only
    const auto config = daemon::read_config(command_line);
    EXPECT_TRUE(fs::equivalent(config.shipped, std::getenv("VIBSCORE_CLEFS"))) << config.shipped;
}

}  // namespace
}  // namespace vibscore
