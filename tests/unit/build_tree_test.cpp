// A program run from its build tree finds its checkout's files: meson's own record of the
// source folder (meson-info/meson-info.json), never a path compiled in.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "json/build_tree.hpp"
#include "config.h"
#include "daemon/command_line.hpp"
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
