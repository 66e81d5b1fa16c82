#include "common/atomic_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <iterator>
#include <system_error>

#include "tests/support/support.hpp"

namespace vibscore::daemon {
namespace {

using testing::file_names;
using ::testing::HasSubstr;
using testing::read_file;
using testing::TempDir;

TEST(AtomicFile, CreatesAndReplacesTheContent) {
    TempDir dir;
    const auto path = dir.path() / "a.score.xml";
    write_file_atomically(path, "first, and longer than the second");
    EXPECT_EQ(read_file(path), "first, and longer than the second");
    write_file_atomically(path, "second");
    EXPECT_EQ(read_file(path), "second");
    write_file_atomically(path, "");
    EXPECT_EQ(read_file(path), "");
}

TEST(AtomicFile, LeavesOnlyTheTargetInTheDirectory) {
    TempDir dir;
    for (int i = 0; i < 5; ++i) {
        write_file_atomically(dir.path() / "a.clef.xml", std::string(100'000, 'a' + i));
    }
    EXPECT_EQ(file_names(dir.path()), std::vector<std::string>{"a.clef.xml"});
    EXPECT_EQ(read_file(dir.path() / "a.clef.xml"), std::string(100'000, 'e'));
}

TEST(AtomicFile, GivesTheTargetTheRequestedMode) {
    TempDir dir;
    const auto path = dir.path() / "a";
    write_file_atomically(path, "x");
    struct stat status {};
    ASSERT_EQ(::stat(path.c_str(), &status), 0);
    EXPECT_EQ(status.st_mode & 07777, 0644u);
    write_file_atomically(path, "y", 0600);
    ASSERT_EQ(::stat(path.c_str(), &status), 0);
    EXPECT_EQ(status.st_mode & 07777, 0600u);
}

TEST(AtomicFile, MissingDirectoryIsAnErrorNamingThePath) {
    TempDir dir;
    const auto path = dir.path() / "nowhere" / "a.score.xml";
    try {
        write_file_atomically(path, "x");
        FAIL() << "no error";
    } catch (const std::system_error& error) {
        EXPECT_EQ(error.code().value(), ENOENT);
        EXPECT_THAT(error.what(), HasSubstr(path.string()));
        EXPECT_THAT(error.what(), HasSubstr("No such file or directory"));
    }
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "nowhere"));
}

TEST(AtomicFile, AFailedRenameRemovesTheTemporaryAndKeepsTheTarget) {
    TempDir dir;
    // A directory in the target's place makes the rename fail after the data was written.
    dir.write("a.score.xml/keep", "kept");
    try {
        write_file_atomically(dir.path() / "a.score.xml", "x");
        FAIL() << "no error";
    } catch (const std::system_error& error) {
        EXPECT_THAT(error.what(), HasSubstr((dir.path() / "a.score.xml").string()));
    }
    EXPECT_EQ(file_names(dir.path()), std::vector<std::string>{"a.score.xml"});
    EXPECT_EQ(read_file(dir.path() / "a.score.xml" / "keep"), "kept");
}

TEST(AtomicFile, RemovesDurablyAndSaysWhetherThereWasAFile) {
    TempDir dir;
    const auto path = dir.write("a.clef.xml", "x");
    EXPECT_TRUE(remove_file_durably(path));
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_FALSE(remove_file_durably(path));
}

TEST(AtomicFile, RemoveFailureNamesThePath) {
    TempDir dir;
    dir.write("d/x", "x");
    try {
        remove_file_durably(dir.path() / "d");  // unlink refuses a directory
        FAIL() << "no error";
    } catch (const std::system_error& error) {
        EXPECT_THAT(error.what(), HasSubstr((dir.path() / "d").string()));
    }
}

TEST(AtomicFile, TellsTemporaryFileNames) {
    EXPECT_TRUE(is_temporary_file_name(".a.score.xml.tmp-Ab12Cd"));
    EXPECT_TRUE(is_temporary_file_name(".x.tmp-"));
    EXPECT_FALSE(is_temporary_file_name("a.score.xml"));
    EXPECT_FALSE(is_temporary_file_name(".hidden"));
    EXPECT_FALSE(is_temporary_file_name("a.tmp-123"));
}

TEST(AtomicFile, RemovesStaleTemporariesOnly) {
    TempDir dir;
    dir.write(".a.score.xml.tmp-Ab12Cd", "<VibSc");
    dir.write(".b.clef.xml.tmp-000000", "");
    dir.write("a.score.xml", "kept");
    dir.write(".hidden", "kept");
    const auto removed = remove_stale_temporaries(dir.path());
    EXPECT_EQ(removed.size(), 2u);
    EXPECT_EQ(file_names(dir.path()), (std::vector<std::string>{".hidden", "a.score.xml"}));
}

TEST(AtomicFile, ListingAMissingDirectoryNamesIt) {
    TempDir dir;
    try {
        remove_stale_temporaries(dir.path() / "missing");
        FAIL() << "no error";
    } catch (const std::system_error& error) {
        EXPECT_THAT(error.what(), HasSubstr((dir.path() / "missing").string()));
    }
}

}  // namespace
}  // namespace vibscore::daemon
