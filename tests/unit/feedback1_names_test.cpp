// dbus/feedback1_names.hpp is the one spelling of vibscore-feedback's names in the code; the
// files that say them to the world (the D-Bus activation file, the interface XML that documents
// each member and error) are checked against it here, so the two cannot drift apart.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "dbus/feedback1_names.hpp"
#include "json/build_tree.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// A file of the checkout this test program was built from.
std::string checkout_file(const std::string& relative) {
    const auto source = source_tree_of(fs::read_symlink("/proc/self/exe"));
    if (!source) {
        throw std::runtime_error("this test does not lie in a meson build tree");
    }
    const auto path = *source / relative;
    const auto text = testing::read_file(path);
    if (text.empty()) {
        throw std::runtime_error(path.string() + ": empty or unreadable");
    }
    return text;
}

TEST(Feedback1Names, TheBusNameIsTheOneTheActivationFileStartsVibscoreFeedbackFor) {
    EXPECT_THAT(checkout_file("feedback/org.sigxcpu.Feedback.service.in"),
                HasSubstr("\nName=" + std::string(feedback1::kBusName) + "\n"));
}

TEST(Feedback1Names, EachInterfaceIsOneTheInterfaceFilesDeclare) {
    const auto feedbackd = checkout_file("feedback/org.sigxcpu.Feedback.xml");
    EXPECT_THAT(feedbackd, HasSubstr("<interface name=\"" +
                                     std::string(feedback1::kFeedbackdInterface) + "\">"));
    EXPECT_THAT(feedbackd,
                HasSubstr("<interface name=\"" + std::string(feedback1::kHapticInterface) + "\">"));
    EXPECT_THAT(checkout_file("feedback/org.vibscore.Feedback1.xml"),
                HasSubstr("<interface name=\"" + std::string(feedback1::kInterface) + "\">"));
}

TEST(Feedback1Names, TheObjectPathAndBusNameAreTheOnesTheInterfaceFilesDocument) {
    for (const char* file :
         {"feedback/org.sigxcpu.Feedback.xml", "feedback/org.vibscore.Feedback1.xml"}) {
        const auto text = checkout_file(file);
        EXPECT_THAT(text, HasSubstr(feedback1::kObjectPath)) << file;
        EXPECT_THAT(text, HasSubstr(feedback1::kBusName)) << file;
    }
}

TEST(Feedback1Names, VibscoresOwnErrorsBeginWithThePrefixAndAreDocumentedWhereTheySend) {
    const auto documented = checkout_file("feedback/org.vibscore.Feedback1.xml");
    for (const char* name : {feedback1::errors::kLimitExceeded, feedback1::errors::kBusy}) {
        EXPECT_THAT(name, StartsWith(std::string(feedback1::errors::kErrorPrefix)));
        EXPECT_GT(std::string(name).size(), feedback1::errors::kErrorPrefix.size()) << name;
        EXPECT_THAT(documented, HasSubstr(name));
    }
    // The generic ones are the bus's, not ours.
    for (const char* name : {feedback1::errors::kInvalidArgs, feedback1::errors::kFailed}) {
        EXPECT_THAT(name, StartsWith("org.freedesktop.DBus.Error."));
        EXPECT_THAT(documented, HasSubstr(name));
    }
}

}  // namespace
}  // namespace vibscore
