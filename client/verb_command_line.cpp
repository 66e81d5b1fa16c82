#include "client/verb_command_line.hpp"

#include <iostream>
#include <utility>

#include "client/bus_verbs.hpp"
#include "client/daemon_documents.hpp"
#include "client/offline_verbs.hpp"
#include "common/closest_name.hpp"
#include "config.h"

namespace vibscore::client {

namespace {

// A command of the table as CLI11 holds it, with the handler its options feed.
struct Declared {
    const CLI::App* command;
    VerbHandler handler;
};

void declare_verbs(CLI::App& parent, const std::vector<Verb>& table, VerbContext& context,
                   std::vector<Declared>& declared) {
    for (const auto& verb : table) {
        auto* command = parent.add_subcommand(std::string(verb.name), std::string(verb.help));
        if (!verb.footer.empty()) {
            command->footer(std::string(verb.footer));
        }
        if (!verb.subverbs.empty()) {
            command->require_subcommand(1);
            declare_verbs(*command, verb.subverbs, context, declared);
        }
        if (verb.declare != nullptr) {
            declared.push_back({command, verb.declare(*command, context)});
        }
    }
}

// One line per command of `table` under `parent`: its words, then each option name, a valued
// one followed by '=', then what each argument completes to after ':' ("clef fit -h --help
// --actuator= -o= --output= --clefs= :@clefs,*.xml").
void print_completion_words(const CLI::App& parent, const std::vector<Verb>& table,
                            const std::string& before, std::ostream& out) {
    for (const auto& verb : table) {
        const auto* command = parent.get_subcommand(std::string(verb.name));
        const std::string words = before + command->get_name();
        out << words;
        for (const auto* option : command->get_options()) {
            if (!option->nonpositional()) {
                continue;
            }
            const char* valued = option->get_expected_max() > 0 ? "=" : "";
            for (const auto& name : option->get_snames()) {
                out << " -" << name << valued;
            }
            for (const auto& name : option->get_lnames()) {
                out << " --" << name << valued;
            }
        }
        for (const auto& argument : verb.completion) {
            out << " :" << argument;
        }
        out << "\n";
        print_completion_words(*command, verb.subverbs, words + " ", out);
    }
}

// CLI11 says only "A subcommand is required" both when no verb is given and when a verb made of
// sub-verbs lacks one; name what is missing instead. A misspelt verb never gets here
// (unknown_verb_message).
std::string usage_error_message(const CLI::App& app, const CLI::ParseError& error) {
    const auto extras = app.remaining();
    const auto verbs = app.get_subcommands();
    if (!verbs.empty()) {
        const auto* verb = verbs.front();
        if (verb->get_require_subcommand_min() > 0 && verb->get_subcommands().empty()) {
            std::string message = verb->get_name() + " needs a command:";
            for (const auto* sub : verb->get_subcommands({})) {
                message += " " + sub->get_name();
            }
            return message;
        }
        return error.what();
    }
    if (extras.empty()) {
        return "a command is required (see --help for the commands)";
    }
    if (extras.front().starts_with("-")) {
        return "unknown option " + extras.front();
    }
    return "unexpected argument " + extras.front();
}

}  // namespace

std::string unknown_verb_message(const std::vector<Verb>& table,
                                 const std::vector<std::string>& words) {
    const std::vector<Verb>* level = &table;
    std::string before;  // the verb words already read ("clef ")
    for (const auto& word : words) {
        if (word == "--") {
            break;
        }
        if (word.starts_with("-")) {
            continue;  // before a verb only --help and --version, which take no value
        }
        std::vector<std::string> names;
        const Verb* found = nullptr;
        for (const auto& verb : *level) {
            names.emplace_back(verb.name);
            if (verb.name == word) {
                found = &verb;
            }
        }
        if (found == nullptr) {
            std::string message = "unknown command \"" + before + word + "\"";
            if (const auto meant = closest_name(word, names)) {
                message += " (did you mean " + before + *meant + "?)";
            }
            message += before.empty()
                           ? "; the commands are:"
                           : "; the commands of " + before.substr(0, before.size() - 1) + " are:";
            for (const auto& name : names) {
                message += " " + name;
            }
            return message;
        }
        if (found->subverbs.empty()) {
            return "";
        }
        before += word + " ";
        level = &found->subverbs;
    }
    return "";
}

int run_command_line(int argc, char** argv) {
    CLI::App app{
        "vibscore - compose, check and play vibrotactile scores.\n"
        "Exit status: 0 success, 1 invalid document or failed operation, 2 usage error.\n"
        "The docs/NAME.md below are in " VIBSCORE_CLIENT_DOCDIR " once installed; man vibscore.",
        "vibscore"};
    app.set_version_flag("--version", std::string("vibscore ") + VIBSCORE_VERSION);
    app.require_subcommand(1);

    VerbContext context;
    context.clef_search.registry = registry_clef_fetcher();
    context.clef_search.registry_score = registry_score_fetcher();
    std::vector<Declared> declared;
    declare_verbs(app, verbs(), context, declared);

    const std::vector<std::string> words(argv + std::min(argc, 1), argv + argc);
    if (words.size() == 1 && words.front() == kCompletionWordsFlag) {
        print_completion_words(app, verbs(), "", std::cout);
        return exit_ok;
    }
    if (const auto unknown = unknown_verb_message(verbs(), words); !unknown.empty()) {
        std::cerr << "vibscore: " << unknown << "\nRun 'vibscore --help' for usage.\n";
        return exit_usage;
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "vibscore: " << usage_error_message(app, e)
                  << "\nRun 'vibscore --help' for usage.\n";
        return exit_usage;
    }
    for (const auto& [command, handler] : declared) {
        if (command->parsed()) {
            return handler();
        }
    }
    // require_subcommand(1) at every level: a parse that chose no verb has thrown above.
    std::cerr << "vibscore: no command was chosen\n";
    return exit_usage;
}

}  // namespace vibscore::client
