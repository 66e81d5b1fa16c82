#include "feedback/user_scores.hpp"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <stdexcept>
#include <system_error>

#include "common/atomic_file.hpp"
#include "common/quoted_text.hpp"
#include "feedback/json_fields.hpp"
#include "json/json_document.hpp"
#include "score/registry_names.hpp"

namespace vibscore::feedback {

namespace {

constexpr const char* kEvents = "events";

nlohmann::ordered_json to_json(const JsonValue& value) {
    switch (value.kind) {
        case JsonValue::Kind::null:
            return nullptr;
        case JsonValue::Kind::boolean:
            return value.boolean;
        case JsonValue::Kind::number:
            if (value.integral && value.number >= -9.0e15 && value.number <= 9.0e15) {
                return static_cast<long long>(value.number);
            }
            return value.number;
        case JsonValue::Kind::string:
            return value.text;
        case JsonValue::Kind::array: {
            auto array = nlohmann::ordered_json::array();
            for (const auto& item : value.items) {
                array.push_back(to_json(item));
            }
            return array;
        }
        case JsonValue::Kind::object:
            break;
    }
    auto object = nlohmann::ordered_json::object();
    for (const auto& member : value.members) {
        object[member.key] = to_json(member.value);
    }
    return object;
}

bool file_exists(const std::filesystem::path& file) {
    std::error_code error;
    return std::filesystem::exists(file, error);
}

}  // namespace

std::filesystem::path user_scores_path() {
    const char* config = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    std::filesystem::path base;
    if (config != nullptr && *config == '/') {
        base = config;
    } else if (home != nullptr && *home != '\0') {
        base = std::filesystem::path(home) / ".config";
    } else {
        throw std::runtime_error("neither XDG_CONFIG_HOME nor HOME is set: no config directory");
    }
    return base / "vibscore" / "feedback.json";
}

void make_user_directory(const std::filesystem::path& directory) {
    if (file_exists(directory)) {
        return;
    }
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    if (error) {
        throw std::system_error(error, "cannot make " + directory.string());
    }
    // The user's own: others need not read which score plays for what.
    std::filesystem::permissions(directory, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::replace, error);
}

void check_event_and_score(const std::string& event, const std::string& score) {
    if (!is_valid_name(event)) {
        throw std::invalid_argument("event " + quoted_text(event) + " is not an event name (" +
                                    std::string(kNameRule) + ")");
    }
    if (!score.empty() && !is_valid_name(score)) {
        throw std::invalid_argument("score " + quoted_text(score) + " is not a score name (" +
                                    std::string(kNameRule) + ")");
    }
}

bool is_event_name(std::string_view name) {
    if (name.empty() || name.size() > kMaxEventNameLength || name.front() == '-' ||
        name.back() == '-') {
        return false;
    }
    char previous = '\0';
    for (const char c : name) {
        const bool word = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
        if (!word && !(c == '-' && previous != '-')) {
            return false;
        }
        previous = c;
    }
    return true;
}

namespace {

UserScores scores_in(const JsonDocument& document, std::vector<Diagnostic>& warnings) {
    UserScores scores;
    const JsonFields json(document);
    const JsonValue& root = json.object(document.root());
    for (const auto& member : root.members) {
        if (member.key != kEvents) {
            warnings.push_back({document.where(member.key_offset),
                                "unknown member \"" + member.key + "\" ignored"});
        }
    }
    const JsonValue* events = root.find(kEvents);
    if (events == nullptr) {
        return scores;
    }
    // Entry by entry: one the user mistyped must not cost them all the others.
    for (const auto& member : json.object(*events).members) {
        const std::string ignored = ": the entry is ignored";
        if (member.value.kind != JsonValue::Kind::string) {
            warnings.push_back({document.where(member.value),
                                "expected a string, found " + describe(member.value) + ignored});
            continue;
        }
        const std::string& score = member.value.text;
        if (!is_valid_name(member.key)) {
            warnings.push_back({document.where(member.key_offset),
                                "event " + quoted_text(member.key) + " is not an event name (" +
                                    std::string(kNameRule) + ")" + ignored});
            continue;
        }
        if (!is_valid_name(score)) {
            warnings.push_back({document.where(member.value),
                                "score " + quoted_text(score) + " is not a score name (" +
                                    std::string(kNameRule) + ")" + ignored});
            continue;
        }
        if (scores.size() == kMaxAssignments) {
            warnings.push_back(
                {document.where(member.key_offset),
                 "more than " + std::to_string(kMaxAssignments) +
                     " events have a score of your own: this one and those after it are "
                     "ignored (the limit, docs/feedbackd.md)"});
            break;
        }
        scores[member.key] = score;
    }
    return scores;
}

}  // namespace

UserScores read_user_scores(const std::filesystem::path& file, std::vector<Diagnostic>& warnings) {
    if (!file_exists(file)) {
        return {};
    }
    // The bus thread reads it: a FIFO or a device there could hold it without end.
    std::error_code error;
    if (std::filesystem::status(file, error).type() != std::filesystem::file_type::regular) {
        throw DocumentError({file.string()}, "not a regular file, not read");
    }
    return scores_in(read_json_file(file.string()), warnings);
}

void store_user_score(const std::filesystem::path& file, const std::string& event,
                      const std::string& score) {
    check_event_and_score(event, score);
    if (score.empty() && !file_exists(file)) {
        return;  // nothing chosen, nothing to take back
    }
    auto root = nlohmann::ordered_json::object();
    if (file_exists(file)) {
        // Read strictly: a file that does not read is the user's to mend, not ours to replace.
        // Read once: what is checked is what is kept.
        const JsonDocument document = read_json_file(file.string());
        std::vector<Diagnostic> warnings;
        scores_in(document, warnings);
        root = to_json(document.root());
    }
    auto& events = root[kEvents];
    if (!events.is_object()) {
        events = nlohmann::ordered_json::object();
    }
    if (score.empty()) {
        events.erase(event);
    } else {
        if (!events.contains(event) && events.size() >= kMaxAssignments) {
            throw AssignmentLimit(std::to_string(events.size()) +
                                  " events already have a score of your own in " + file.string() +
                                  ", the limit is " + std::to_string(kMaxAssignments) +
                                  ": give one back to the theme first (vibscore assign EVENT "
                                  "--default)");
        }
        events[event] = score;
    }
    const std::string text = root.dump(2) + "\n";
    // Never write what the reader would refuse as a whole at the next start.
    if (text.size() > max_json_file_bytes) {
        throw AssignmentLimit(file.string() + " would be " + std::to_string(text.size()) +
                              " bytes, above the reader's limit of " +
                              std::to_string(max_json_file_bytes) +
                              " (members other than \"events\" take the room): not written");
    }
    make_user_directory(file.parent_path());
    daemon::write_file_atomically(file, text, 0600);
}

std::vector<std::filesystem::path> remove_stale_temporaries_of(const std::filesystem::path& file) {
    // write_file_atomically's names: "." + file name + ".tmp-" + six characters of mkostemp.
    const std::string prefix = "." + file.filename().string() + ".tmp-";
    std::vector<std::filesystem::path> removed;
    std::error_code error;
    std::filesystem::directory_iterator entries(file.parent_path(), error);
    if (error) {
        if (error == std::errc::no_such_file_or_directory) {
            return removed;
        }
        throw std::system_error(error, "cannot list " + file.parent_path().string());
    }
    for (const auto& entry : entries) {
        const std::string name = entry.path().filename().string();
        if (!name.starts_with(prefix)) {
            continue;
        }
        std::filesystem::remove(entry.path(), error);
        if (error) {
            throw std::system_error(
                error, "cannot remove the stale temporary file " + entry.path().string());
        }
        removed.push_back(entry.path());
    }
    return removed;
}

}  // namespace vibscore::feedback
