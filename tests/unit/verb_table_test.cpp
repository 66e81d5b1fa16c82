// The client's verb table (client/verb_table.cpp) against what is made from it or written beside
// it: the general and each verb's --help, the refusal of an unknown verb, the completion words,
// the bash completion's hand-written part and the manual page's entries. Runs the built client.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "tests/support/run_command.hpp"

namespace vibscore {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using ::testing::StartsWith;

const std::string kSeeHelp = "\nRun 'vibscore --help' for usage.\n";

testing::CommandResult vibscore(std::vector<std::string> args) {
    args.insert(args.begin(), testing::required_env("VIBSCORE"));
    return testing::run_command(args);
}

std::string source_file(const std::string& path) {
    const std::string full = testing::required_env("VIBSCORE_SOURCE_ROOT") + "/" + path;
    std::ifstream in(full);
    EXPECT_TRUE(in) << full;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// `vibscore --completion-words`: each command's words ("clef fit") to its options, a valued one
// without its '='.
std::map<std::string, std::set<std::string>> completion_words() {
    const auto result = vibscore({"--completion-words"});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    std::map<std::string, std::set<std::string>> commands;
    std::istringstream lines(result.out);
    for (std::string line; std::getline(lines, line);) {
        std::istringstream words(line);
        std::string command;
        std::set<std::string> options;
        for (std::string word; words >> word;) {
            if (word.starts_with("-")) {
                options.insert(word.ends_with("=") ? word.substr(0, word.size() - 1) : word);
            } else if (word.starts_with(":")) {
                continue;  // what an argument completes to
            } else {
                command += (command.empty() ? "" : " ") + word;
            }
        }
        commands[command] = options;
    }
    return commands;
}

// The top-level verbs of the completion words, in their order.
std::vector<std::string> verbs_of(const std::map<std::string, std::set<std::string>>& commands) {
    std::vector<std::string> verbs;
    for (const auto& [command, options] : commands) {
        if (command.find(' ') == std::string::npos) {
            verbs.push_back(command);
        }
    }
    return verbs;
}

TEST(VerbTable, AnUnknownVerbIsRefusedTheSameWayWithOrWithoutHelp) {
    const std::string refusal =
        "vibscore: unknown command \"calibrat\" (did you mean calibrate?); the commands are: "
        "check render convert clef info play stop list get compose delete drivers driver show "
        "assign calibrate edit" +
        kSeeHelp;
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"calibrat"}, {"calibrat", "--help"}, {"--help", "calibrat"}, {"calibrat", "-h"}}) {
        const auto result = vibscore(args);
        EXPECT_EQ(result.exit_code, 2) << args.front();
        EXPECT_EQ(result.err, refusal) << args.front();
        EXPECT_THAT(result.out, IsEmpty());
    }
}

TEST(VerbTable, AnUnknownSubVerbIsRefusedNamingTheClosestWithOrWithoutHelp) {
    for (const auto& args :
         std::vector<std::vector<std::string>>{{"clef", "fitt"}, {"clef", "fitt", "--help"}}) {
        const auto result = vibscore(args);
        EXPECT_EQ(result.exit_code, 2);
        EXPECT_EQ(result.err,
                  "vibscore: unknown command \"clef fitt\" (did you mean clef fit?); the "
                  "commands of clef are: fit" +
                      kSeeHelp);
    }
    // Too far from any verb to be a typo: no guess, still the list.
    const auto far = vibscore({"clef", "stretch", "--help"});
    EXPECT_EQ(far.exit_code, 2);
    EXPECT_EQ(far.err, "vibscore: unknown command \"clef stretch\"; the commands of clef are: fit" +
                           kSeeHelp);
}

TEST(VerbTable, AVerbMadeOfSubVerbsWithoutOneNamesThem) {
    const auto result = vibscore({"clef"});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_EQ(result.err, "vibscore: clef needs a command: fit" + kSeeHelp);
}

TEST(VerbTable, EveryVerbsHelpIsItsOwnAndListsItsOptions) {
    const auto general = vibscore({"--help"});
    ASSERT_EQ(general.exit_code, 0);
    const auto commands = completion_words();
    EXPECT_GE(commands.size(), 18u) << "17 verbs and clef fit";
    for (const auto& [command, options] : commands) {
        std::vector<std::string> args;
        std::istringstream words(command);
        for (std::string word; words >> word;) {
            args.push_back(word);
        }
        args.push_back("--help");
        const auto help = vibscore(args);
        EXPECT_EQ(help.exit_code, 0) << command << "\n" << help.err;
        EXPECT_THAT(help.out, HasSubstr("Usage: vibscore " + command + " ")) << command;
        EXPECT_THAT(help.out, Not(HasSubstr("Exit status:"))) << command << ": the general help";
        for (const auto& option : options) {
            EXPECT_THAT(help.out, HasSubstr(option)) << command;
        }
        if (args.size() == 2) {
            // Its one line of the general help is the first of its own.
            const std::string first = help.out.substr(0, help.out.find('\n'));
            EXPECT_THAT(general.out, HasSubstr("  " + command)) << command;
            EXPECT_THAT(general.out, HasSubstr(first)) << command;
        }
    }
    EXPECT_TRUE(commands.contains("clef fit"));
    EXPECT_TRUE(commands.at("clef fit").contains("--output"));
    EXPECT_TRUE(commands.at("calibrate").contains("--estimate"));
}

// The part of completion/vibscore.bash still written by hand (what follows an option or a verb)
// names only options and verbs the table has: a renamed or removed one fails here.
TEST(VerbTable, TheBashCompletionNamesOnlyTheTablesVerbsAndOptions) {
    const std::string script = source_file("client/completion/vibscore.bash");
    const auto commands = completion_words();
    std::set<std::string> options;
    for (const auto& [command, own] : commands) {
        options.insert(own.begin(), own.end());
    }
    const auto verbs = verbs_of(commands);
    const std::set<std::string> verb_set(verbs.begin(), verbs.end());
    // The options of `case $prev in` labels ("--svg|--png)").
    const std::regex label(R"(^\s+((-[-a-z]+)(\|-[-a-z]+)*)\)\s*$)");
    std::size_t labelled = 0;
    std::istringstream lines(script);
    for (std::string line; std::getline(lines, line);) {
        std::smatch match;
        if (std::regex_match(line, match, label)) {
            std::istringstream names(match[1].str());
            for (std::string name; std::getline(names, name, '|');) {
                EXPECT_TRUE(options.contains(name)) << "vibscore.bash completes " << name;
                ++labelled;
            }
        }
    }
    EXPECT_GE(labelled, 10u);
    // The verbs of `case $verb in` labels ("play|show|edit)") and of [[ $verb == NAME ]].
    const std::regex verb_label(R"(^\s+([a-z]+(\|[a-z]+)*)\)\s*$)");
    const std::regex verb_test(R"(\$verb == ([a-z]+))");
    std::size_t named = 0;
    std::istringstream again(script);
    for (std::string line; std::getline(again, line);) {
        std::smatch match;
        if (std::regex_match(line, match, verb_label)) {
            std::istringstream names(match[1].str());
            for (std::string name; std::getline(names, name, '|');) {
                EXPECT_TRUE(verb_set.contains(name)) << "vibscore.bash completes verb " << name;
                ++named;
            }
        }
        for (std::sregex_iterator it(line.begin(), line.end(), verb_test), end; it != end; ++it) {
            EXPECT_TRUE(verb_set.contains((*it)[1].str()))
                << "vibscore.bash tests verb " << (*it)[1].str();
            ++named;
        }
    }
    EXPECT_GE(named, 3u);
    // The verbs, their options and what their arguments complete to are the table's, not lists
    // in the script.
    EXPECT_THAT(script, HasSubstr("--completion-words"));
    EXPECT_THAT(script, Not(HasSubstr("check render")));
    EXPECT_THAT(script, Not(HasSubstr("case $verb in")));
    // Each source the table names (@scores, @kind, ...) is one the script knows.
    const auto listed = vibscore({"--completion-words"});
    const std::regex source(R"([:,](@[a-z]+))");
    std::size_t sources = 0;
    for (std::sregex_iterator it(listed.out.begin(), listed.out.end(), source), end; it != end;
         ++it) {
        const std::string name = (*it)[1].str();
        EXPECT_TRUE(std::regex_search(script, std::regex("[\\s|]" + name + "[|)]")))
            << "vibscore.bash does not complete " << name;
        ++sources;
    }
    EXPECT_GE(sources, 8u);
}

// The manual page's COMMANDS entries ("check", "clef fit") are the table's commands: an entry for
// a verb the client does not have fails here (the documentation suite checks the other way).
TEST(VerbTable, TheManualPageHasAnEntryForEachCommandAndNoOther) {
    const std::string page = source_file("man/vibscore.1.in");
    const auto commands = completion_words();
    std::set<std::string> expected;
    for (const auto& [command, options] : commands) {
        const bool has_subverbs = std::any_of(commands.begin(), commands.end(), [&](const auto& c) {
            return c.first.starts_with(command + " ");
        });
        if (!has_subverbs) {
            expected.insert(command);
        }
    }
    std::set<std::string> entries;
    std::istringstream lines(page.substr(page.find(".SH COMMANDS"),
                                         page.find(".SH OPTIONS") - page.find(".SH COMMANDS")));
    bool after_tp = false;
    int nested = 0;  // inside .RS/.RE: an entry's options, not a command
    for (std::string line; std::getline(lines, line);) {
        nested += line.starts_with(".RS") ? 1 : line.starts_with(".RE") ? -1 : 0;
        if (after_tp && nested == 0 && line.starts_with(".B")) {
            std::string head = line.substr(line.find(' ') + 1);
            if (head.starts_with("\"")) {
                head = head.substr(1, head.find('"', 1) - 1);
            } else {
                head = head.substr(0, head.find(' '));
            }
            while (head.ends_with(" ")) {
                head.pop_back();
            }
            entries.insert(head);
        }
        after_tp = line.starts_with(".TP");
    }
    EXPECT_EQ(entries, expected);
}

}  // namespace
}  // namespace vibscore
