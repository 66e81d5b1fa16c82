#include "feedback/user_scores.hpp"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <stdexcept>
#include <system_error>

#include "common/json/json_document.hpp"
#include "common/quoted_text.hpp"
#include "daemon/registry/atomic_file.hpp"
#include "feedback/json_fields.hpp"
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

UserScores read_user_scores(const std::filesystem::path& file, std::vector<Diagnostic>& warnings) {
    UserScores scores;
    if (!file_exists(file)) {
        return scores;
    }
    const JsonDocument document = read_json_file(file.string());
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
    for (const auto& member : json.object(*events).members) {
        const std::string score = json.string(member.value);
        if (!is_valid_name(member.key)) {
            throw DocumentError(document.where(member.key_offset),
                                "event " + quoted_text(member.key) + " is not an event name (" +
                                    std::string(kNameRule) + ")");
        }
        if (!is_valid_name(score)) {
            throw json.error(member.value, "score " + quoted_text(score) +
                                               " is not a score name (" + std::string(kNameRule) +
                                               ")");
        }
        scores[member.key] = score;
    }
    return scores;
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
        std::vector<Diagnostic> warnings;
        read_user_scores(file, warnings);
        root = to_json(read_json_file(file.string()).root());
    }
    auto& events = root[kEvents];
    if (!events.is_object()) {
        events = nlohmann::ordered_json::object();
    }
    if (score.empty()) {
        events.erase(event);
    } else {
        events[event] = score;
    }
    make_user_directory(file.parent_path());
    daemon::write_file_atomically(file, root.dump(2) + "\n", 0600);
}

}  // namespace vibscore::feedback
