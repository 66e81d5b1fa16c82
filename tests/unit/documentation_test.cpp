// What a newcomer reads stays true: the manual pages hold every verb and option the programs'
// --help shows and every key of the shipped configuration; each package ships the documents
// its help names, in a doc folder of its own; the README lists each folder once; the
// architecture map shows every folder of code and every thread; no document promises work as
// still to come.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "daemon/config.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/support.hpp"

namespace vibscore {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

fs::path source_root() {
    return testing::required_env("VIBSCORE_SOURCE_ROOT");
}

// Every `from` in `text` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
        text.replace(at, from.size(), to);
    }
    return text;
}

bool is_name_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
}

// The leading run of a-z, 0-9 and '-' of `text`.
std::string name_at(const std::string& text, std::size_t at = 0) {
    auto end = at;
    while (end < text.size() && is_name_char(text[end])) {
        ++end;
    }
    return text.substr(at, end - at);
}

// A manual page's text as it reads: "\-" is "-", font changes and quotes are left out. (No
// std::regex in this file: GCC 12 warns inside it, as registry_test says.)
std::string man_text(const std::string& page) {
    std::string text = testing::read_file(fs::path(testing::required_env("VIBSCORE_MAN")) / page);
    EXPECT_FALSE(text.empty()) << page;
    text = replaced(text, "\\-", "-");
    for (const char* font : {"\\fB", "\\fI", "\\fR", "\\fP", "\""}) {
        text = replaced(text, font, "");
    }
    return text;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
    }
    return lines;
}

// The options of a --help text ("--clefs", "-v", "--colour", "--color"...).
std::set<std::string> options_of(const std::string& help) {
    std::set<std::string> options;
    for (const auto& line : lines_of(help)) {
        if (!line.starts_with("  -")) {
            continue;
        }
        std::istringstream list(line.substr(2, line.find(' ', 2) - 2));
        for (std::string option; std::getline(list, option, ',');) {
            options.insert(option);
        }
    }
    return options;
}

// The verbs under "Subcommands:" of `vibscore --help`.
std::vector<std::string> verbs_of(const std::string& help) {
    std::vector<std::string> verbs;
    bool listed = false;
    for (const auto& line : lines_of(help)) {
        listed = listed || line == "Subcommands:";
        if (listed && line.starts_with("  ") && line.size() > 2 && line[2] >= 'a' &&
            line[2] <= 'z') {
            verbs.push_back(name_at(line, 2));
        }
    }
    return verbs;
}

// Whether `word` stands in `text` as a whole name (no name character on either side).
bool mentions_option(const std::string& text, const std::string& word) {
    for (auto at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
        const auto end = at + word.size();
        if ((at == 0 || !is_name_char(text[at - 1])) &&
            (end == text.size() || !is_name_char(text[end]))) {
            return true;
        }
    }
    return false;
}

// The names right after each `marker` in `text` ("docs/" then "formats" for docs/formats.md).
std::set<std::string> names_after(const std::string& text, const std::string& marker) {
    std::set<std::string> names;
    for (auto at = text.find(marker); at != std::string::npos; at = text.find(marker, at + 1)) {
        names.insert(name_at(text, at + marker.size()));
    }
    return names;
}

std::string help_of(const std::vector<std::string>& argv) {
    const auto result = testing::run_command(argv);
    EXPECT_EQ(result.exit_code, 0) << argv.at(0) << "\n" << result.err;
    return result.out;
}

// Every program has its page, and man renders each as lintian checks it (its groff-message
// tag): no warning, nothing on stderr.
TEST(ManualPages, EachRendersWithoutAWarning) {
    const fs::path man = testing::required_env("VIBSCORE_MAN");
    for (const char* page :
         {"vibscore.1", "vibscored.8", "vibscore-feedback.1", "vibscored.conf.5"}) {
        const auto rendered = testing::run_command(
            {"/usr/bin/env", "LC_ALL=C.UTF-8", "MANROFFSEQ=", "MANWIDTH=80", "man", "--warnings",
             "-E", "UTF-8", "-l", "-Tutf8", "-Z", (man / page).string()});
        EXPECT_EQ(rendered.exit_code, 0) << page << "\n" << rendered.err;
        EXPECT_EQ(rendered.err, "") << page;
        EXPECT_GT(rendered.out.size(), 2000u) << page;
    }
    // A page with a fault is caught, so the check above can fail.
    testing::TempDir dir;
    const auto broken =
        dir.write("broken.1", ".TH BROKEN 1\n.SH NAME\nbroken \\- a page\n.BOGUS x\n");
    const auto rendered =
        testing::run_command({"/usr/bin/env", "LC_ALL=C.UTF-8", "MANROFFSEQ=", "man", "--warnings",
                              "-E", "UTF-8", "-l", "-Tutf8", "-Z", broken.string()});
    EXPECT_THAT(rendered.err, HasSubstr("BOGUS"));
}

// Every program answers --help with its usage on stdout and exit status 0.
TEST(Help, EveryProgramAnswersHelp) {
    for (const char* program : {"VIBSCORE", "VIBSCORED", "VIBSCORE_FEEDBACK"}) {
        const auto result = testing::run_command({testing::required_env(program), "--help"});
        EXPECT_EQ(result.exit_code, 0) << program << "\n" << result.err;
        EXPECT_THAT(result.out, HasSubstr("Usage:")) << program;
        EXPECT_EQ(result.err, "") << program;
    }
}

// The entry of `words` (a verb, or a verb and its subcommand: "clef fit") in a page's text: from
// the line that heads it (".B words..." or ".BI words...") up to the next line that heads
// another of `heads` (each verb and subcommand), or the next section. Empty when there is none.
std::string entry_of(const std::string& page, const std::string& words,
                     const std::set<std::string>& heads) {
    const auto head_of = [&](const std::string& line) -> std::string {
        for (const std::string head : {".B ", ".BI "}) {
            if (!line.starts_with(head)) {
                continue;
            }
            // The longest of `heads` the line starts with, as whole words.
            std::string found;
            for (const auto& candidate : heads) {
                const auto rest = line.substr(head.size());
                if (rest.starts_with(candidate) &&
                    (rest.size() == candidate.size() || !is_name_char(rest[candidate.size()])) &&
                    candidate.size() > found.size()) {
                    found = candidate;
                }
            }
            return found;
        }
        return "";
    };
    std::string entry;
    bool inside = false, after_tp = false;
    for (const auto& line : lines_of(page)) {
        // A verb's entry is headed by the line after a .TP; an option's .TP inside .RS heads no
        // verb (its words are options).
        const std::string head = after_tp ? head_of(line) : "";
        after_tp = line == ".TP";
        if (inside && (line.starts_with(".SH") || line.starts_with(".SS") ||
                       (!head.empty() && head != words))) {
            break;
        }
        inside = inside || head == words;
        if (inside) {
            entry += line + "\n";
        }
    }
    return entry;
}

// Every verb, and every subcommand (clef fit), has an entry of its own, and each option its
// --help shows is in that entry: an option mentioned only under another verb does not count.
TEST(ManualPages, VibscoreHasEveryVerbAndEveryOptionOfItsHelp) {
    const std::string vibscore = testing::required_env("VIBSCORE");
    const std::string page = man_text("vibscore.1");
    const auto verbs = verbs_of(help_of({vibscore, "--help"}));
    EXPECT_GE(verbs.size(), 15u);
    // Each command as its words ("check", "clef fit"), with its --help.
    std::vector<std::pair<std::string, std::string>> commands;
    std::set<std::string> heads;
    for (const auto& verb : verbs) {
        const std::string help = help_of({vibscore, verb, "--help"});
        const auto subcommands = verbs_of(help);
        if (subcommands.empty()) {
            commands.emplace_back(verb, help);
        }
        heads.insert(verb);
        for (const auto& sub : subcommands) {
            commands.emplace_back(verb + " " + sub, help_of({vibscore, verb, sub, "--help"}));
            heads.insert(verb + " " + sub);
        }
    }
    EXPECT_THAT(heads, ::testing::IsSupersetOf({"clef fit", "show", "assign", "calibrate"}));
    for (const auto& [words, help] : commands) {
        const auto entry = entry_of(page, words, heads);
        EXPECT_FALSE(entry.empty()) << "vibscore.1 has no entry for " << words;
        for (const auto& option : options_of(help)) {
            if (option == "-h" || option == "--help") {
                continue;  // every command's, under OPTIONS
            }
            EXPECT_TRUE(mentions_option(entry, option))
                << "vibscore.1's entry for " << words << " lacks " << option;
        }
    }
    for (const auto& option : options_of(help_of({vibscore, "--help"}))) {
        EXPECT_TRUE(mentions_option(page, option)) << "vibscore.1 lacks " << option;
    }
}

// The check above fails where it should: an option named only under another verb's entry.
TEST(ManualPages, AnOptionOnlyInAnotherVerbsEntryIsNotInItsOwn) {
    const std::string page =
        ".SH COMMANDS\n.TP\n.BI render  FILE\nRender.\n.RS\n.TP\n.B --actuator\nthe actuator\n"
        ".RE\n.TP\n.BI show  SCORE\nDraw it.\n.TP\n.BI clef fit  CLEF\nFit.\n--actuator too\n"
        ".SH OPTIONS\n";
    const std::set<std::string> heads{"render", "show", "clef", "clef fit"};
    EXPECT_TRUE(mentions_option(entry_of(page, "render", heads), "--actuator"));
    EXPECT_FALSE(mentions_option(entry_of(page, "show", heads), "--actuator"));
    EXPECT_TRUE(mentions_option(entry_of(page, "clef fit", heads), "--actuator"));
    EXPECT_EQ(entry_of(page, "clef", heads), "");
}

TEST(ManualPages, VibscoredAndVibscoreFeedbackHaveEveryOptionOfTheirHelp) {
    for (const auto& [program, page] : std::vector<std::pair<std::string, std::string>>{
             {"VIBSCORED", "vibscored.8"}, {"VIBSCORE_FEEDBACK", "vibscore-feedback.1"}}) {
        const std::string text = man_text(page);
        const auto options =
            options_of(help_of({testing::required_env(program.c_str()), "--help"}));
        EXPECT_GE(options.size(), 6u) << program;
        for (const auto& option : options) {
            EXPECT_TRUE(mentions_option(text, option)) << page << " lacks " << option;
        }
    }
}

TEST(ManualPages, VibscoredConfHasEverySectionAndKeyOfTheShippedFile) {
    const std::string page = man_text("vibscored.conf.5");
    std::set<std::string> sections, keys;
    for (auto line : lines_of(testing::read_file(source_root() / "etc" / "vibscored.conf"))) {
        line = line.starts_with("# ")  ? line.substr(2)
               : line.starts_with("#") ? line.substr(1)
                                       : line;
        const std::string name = name_at(line, line.starts_with("[") ? 1 : 0);
        if (name.empty()) {
            continue;
        }
        if (line == "[" + name + "]") {
            sections.insert(name);
        } else if (line.starts_with(name + " = ")) {
            keys.insert(name);
        }
    }
    // And every key of [daemon], as the reader's own message lists them.
    try {
        daemon::parse_config("[daemon]\nno-such-key = 1\n", "v.conf");
        ADD_FAILURE() << "no error for an unknown key";
    } catch (const daemon::ConfigError& error) {
        const std::string message = error.what();
        const auto start = message.find("(expected ");
        ASSERT_NE(start, std::string::npos) << message;
        std::string list = message.substr(start + 10, message.find(')', start) - start - 10);
        list = replaced(replaced(list, " or ", ","), " ", "");
        std::istringstream items(list);
        for (std::string key; std::getline(items, key, ',');) {
            keys.insert(key);
        }
    }
    EXPECT_GE(sections.size(), 9u);
    EXPECT_GE(keys.size(), 30u);
    for (const auto& section : sections) {
        EXPECT_THAT(page, HasSubstr("[" + section + "]")) << "vibscored.conf.5 lacks a section";
    }
    for (const auto& key : keys) {
        EXPECT_TRUE(mentions_option(page, key)) << "vibscored.conf.5 lacks " << key;
    }
}

// The lines of debian/PACKAGE.install.
std::set<std::string> installed_by(const std::string& package) {
    std::ifstream in(source_root() / "debian" / (package + ".install"));
    std::set<std::string> paths;
    for (std::string line; std::getline(in, line);) {
        paths.insert(line);
    }
    return paths;
}

TEST(DebianPackages, EachShipsTheDocumentsItsHelpNamesInADocFolderOfItsOwn) {
    const std::string vibscore = testing::required_env("VIBSCORE");
    std::string client_help = help_of({vibscore, "--help"});
    for (const auto& verb : verbs_of(client_help)) {
        client_help += help_of({vibscore, verb, "--help"});
    }
    const std::vector<std::pair<std::string, std::string>> helps = {
        {"vibscore", client_help},
        {"vibscored", help_of({testing::required_env("VIBSCORED"), "--help"}) +
                          testing::read_file(source_root() / "systemd" / "vibscored.service.in")},
        {"vibscore-feedback", help_of({testing::required_env("VIBSCORE_FEEDBACK"), "--help"})}};
    for (const auto& [package, help] : helps) {
        const auto paths = installed_by(package);
        auto named = names_after(help, "docs/");
        named.merge(names_after(help, "@docdir@/"));
        for (auto document : named) {
            if (document == "NAME" || document.empty()) {
                continue;  // "docs/NAME.md" in the top help says where they all are
            }
            document += ".md";
            EXPECT_TRUE(paths.contains("usr/share/doc/" + package + "/" + document))
                << package << "'s help names " << document << ", which it does not install";
        }
        for (const auto& path : paths) {
            if (path.starts_with("usr/share/doc/")) {
                EXPECT_TRUE(path.starts_with("usr/share/doc/" + package + "/"))
                    << package << " installs into another package's doc folder: " << path;
            }
        }
    }
    EXPECT_TRUE(installed_by("vibscore").contains("usr/share/doc/vibscore/formats.md"));
    EXPECT_TRUE(installed_by("vibscore").contains("usr/share/man/man1/vibscore.1"));
    EXPECT_TRUE(installed_by("vibscored").contains("usr/share/man/man8/vibscored.8"));
    EXPECT_TRUE(installed_by("vibscored").contains("usr/share/man/man5/vibscored.conf.5"));
    EXPECT_TRUE(
        installed_by("vibscore-feedback").contains("usr/share/man/man1/vibscore-feedback.1"));
}

TEST(DebianPackages, TheChangelogNamesEveryPackageAndTheMaintainerIsTheControlFiles) {
    const std::string control = testing::read_file(source_root() / "debian" / "control");
    const std::string changelog = testing::read_file(source_root() / "debian" / "changelog");
    const auto packages = names_after(control, "\nPackage: ");
    EXPECT_EQ(packages.size(), 4u);
    for (const auto& package : packages) {
        EXPECT_TRUE(mentions_option(changelog, package))
            << "the changelog does not name " << package;
    }
    const auto at = control.find("\nMaintainer: ");
    ASSERT_NE(at, std::string::npos);
    const std::string maintainer = control.substr(at + 13, control.find('\n', at + 1) - at - 13);
    EXPECT_THAT(changelog, HasSubstr(" -- " + maintainer + "  "));
}

TEST(Help, ComposeDeleteAndDriverNamePolkitFirst) {
    const std::string vibscore = testing::required_env("VIBSCORE");
    const std::string help = help_of({vibscore, "--help"});
    for (const std::string verb : {"compose", "delete", "driver"}) {
        const std::string own = help_of({vibscore, verb, "--help"});
        EXPECT_THAT(own, HasSubstr("(polkit: org.vibscore.")) << verb;
        EXPECT_THAT(own, Not(HasSubstr("(root or group vibscore"))) << verb;
    }
    EXPECT_THAT(help, Not(HasSubstr("(root or group vibscore")));
    // info takes a registry name too, and says so in its argument's name.
    EXPECT_THAT(help_of({vibscore, "info", "--help"}),
                HasSubstr("Usage: vibscore info [OPTIONS] SCORE"));
}

// The rows of README.md's "Where things are" table, by the paths in their first column.
TEST(Readme, WhereThingsAreListsEachPathOnce) {
    std::ifstream in(source_root() / "README.md");
    std::map<std::string, int> rows_of;
    bool in_table = false;
    for (std::string line; std::getline(in, line);) {
        if (line.starts_with("## ")) {
            in_table = line == "## Where things are";
            continue;
        }
        if (!in_table || !line.starts_with("| `")) {
            continue;
        }
        const std::string first = line.substr(1, line.find(" |", 1));
        for (auto open = first.find('`'); open != std::string::npos;
             open = first.find('`', first.find('`', open + 1) + 1)) {
            const auto close = first.find('`', open + 1);
            ++rows_of[first.substr(open + 1, close - open - 1)];
            if (close == std::string::npos) {
                break;
            }
        }
    }
    EXPECT_GE(rows_of.size(), 15u);
    for (const auto& [path, rows] : rows_of) {
        EXPECT_EQ(rows, 1) << path << " is in " << rows << " rows";
    }
}

// Every folder that holds code, outside tests/ (docs/testing.md maps those) and build trees.
std::set<std::string> code_folders() {
    std::set<std::string> folders;
    const fs::path root = source_root();
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
         ++it) {
        const std::string name = it->path().filename().string();
        if (it->is_directory() && (name.starts_with(".") || name == "tests" || name == "debian" ||
                                   name == "corpus" || fs::exists(it->path() / "meson-info"))) {
            it.disable_recursion_pending();
            continue;
        }
        const std::string extension = it->path().extension().string();
        if (it->is_regular_file() && (extension == ".cpp" || extension == ".hpp" ||
                                      extension == ".c" || extension == ".h")) {
            const auto folder = fs::relative(it->path().parent_path(), root).string();
            if (folder != ".") {
                folders.insert(folder + "/");
            }
        }
    }
    return folders;
}

// Whether `folder` ("daemon/") stands in `text` as a path of its own: "daemon/drivers/" and
// "tests/daemon/" do not show "daemon/".
bool mentions_folder(const std::string& text, const std::string& folder) {
    for (auto at = text.find(folder); at != std::string::npos; at = text.find(folder, at + 1)) {
        const auto end = at + folder.size();
        if ((at == 0 ||
             !(is_name_char(text[at - 1]) || text[at - 1] == '/' || text[at - 1] == '_')) &&
            (end == text.size() || !(is_name_char(text[end]) || text[end] == '_'))) {
            return true;
        }
    }
    return false;
}

TEST(Architecture, TheMapShowsEveryFolderOfCodeAndEveryThread) {
    const std::string map = testing::read_file(source_root() / "docs" / "architecture.md");
    const auto folders = code_folders();
    EXPECT_GE(folders.size(), 15u);
    for (const auto& folder : folders) {
        EXPECT_TRUE(mentions_folder(map, folder)) << "docs/architecture.md lacks " << folder;
    }
    for (const char* part :
         {"tests/", "bus thread", "playback thread", "PWM thread", "virtual vibra", "polkit",
          "watchdog", "vibscore-feedback", "driver = auto"}) {
        EXPECT_THAT(map, HasSubstr(part));
    }
}

// The top-level folders of the checkout a newcomer sees (build trees and hidden folders aside).
std::set<std::string> top_level_folders() {
    std::set<std::string> folders;
    for (const auto& entry : fs::directory_iterator(source_root())) {
        const std::string name = entry.path().filename().string();
        if (entry.is_directory() && !name.starts_with(".") &&
            !fs::exists(entry.path() / "meson-info")) {
            folders.insert(name + "/");
        }
    }
    return folders;
}

// The library targets the product's meson.build files declare (tests, benches and fuzz targets
// build their own helpers, which the map does not draw).
std::set<std::string> product_library_targets() {
    std::set<std::string> targets;
    const fs::path root = source_root();
    for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator();
         ++it) {
        const std::string name = it->path().filename().string();
        if (it->is_directory() && (name.starts_with(".") || fs::exists(it->path() / "meson-info") ||
                                   (it->path().parent_path() == root &&
                                    (name == "tests" || name == "bench" || name == "fuzz")))) {
            it.disable_recursion_pending();
            continue;
        }
        if (name != "meson.build") {
            continue;
        }
        const std::string text = testing::read_file(it->path());
        for (const std::string call : {"static_library('", "shared_library('"}) {
            for (auto at = text.find(call); at != std::string::npos; at = text.find(call, at + 1)) {
                const auto begin = at + call.size();
                targets.insert(text.substr(begin, text.find('\'', begin) - begin));
            }
        }
    }
    return targets;
}

TEST(Architecture, TheMapNamesEveryTopLevelFolderAndEveryLibraryTarget) {
    const std::string map = testing::read_file(source_root() / "docs" / "architecture.md");
    const auto folders = top_level_folders();
    EXPECT_GE(folders.size(), 20u);
    for (const auto& folder : folders) {
        EXPECT_TRUE(mentions_folder(map, folder)) << "docs/architecture.md lacks " << folder;
    }
    const auto targets = product_library_targets();
    EXPECT_GE(targets.size(), 20u);
    for (const auto& target : targets) {
        EXPECT_TRUE(mentions_folder(map, target)) << "docs/architecture.md lacks " << target;
    }
}

TEST(Docs, NoneStillPromisesTheWorkOfALaterIssue) {
    for (const auto& entry : fs::recursive_directory_iterator(source_root() / "docs")) {
        if (entry.path().extension() != ".md") {
            continue;
        }
        std::string text = testing::read_file(entry.path());
        std::transform(text.begin(), text.end(), text.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        for (const char* promise : {"later issue", "future issue", "coming issue", "next issue"}) {
            EXPECT_THAT(text, Not(HasSubstr(promise))) << entry.path();
        }
    }
}

}  // namespace
}  // namespace vibscore
