#include "feedback/feedbackd_theme.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "common/number_text.hpp"

namespace vibscore::feedback {

namespace {

constexpr double kOldScaleFull = 0x7fff;     // 0.0.3's periodic magnitudes: the kernel's full
constexpr long long kMaxMs = 3'600'000;      // a score lasts at most an hour
constexpr long long kMaxCount = 0x7fffffff;  // the count property's range (G_MAXINT)

// The members every vibra feedback has (FbdFeedbackBase, FbdFeedbackVibra).
constexpr std::array<std::string_view, 3> kVibraMembers{"event-name", "type", "duration"};

class FileReader {
  public:
    explicit FileReader(const JsonFields& json) : json_(json) {}

    FeedbackdThemeFile read() {
        const JsonValue& root = json_.object(json_.document().root());
        file_.path = json_.document().file();
        file_.name_at = {file_.path};
        for (const auto& member : root.members) {
            if (member.key == "name") {
                file_.name = json_.string(member.value);
                file_.name_at = json_.where(member.value);
            } else if (member.key == "parent-name") {
                file_.parent_name = json_.string(member.value);
                file_.parent_at = json_.where(member.value);
            } else if (member.key == "profiles") {
                for (const auto& profile : json_.array(member.value).items) {
                    read_profile(profile);
                }
            } else {
                warn(member.key_offset, "unknown member \"" + member.key + "\" ignored");
            }
        }
        // In the order of the file, whatever order the members were read in.
        std::stable_sort(file_.warnings.begin(), file_.warnings.end(),
                         [](const Diagnostic& a, const Diagnostic& b) {
                             return std::pair(a.where.line, a.where.column) <
                                    std::pair(b.where.line, b.where.column);
                         });
        return std::move(file_);
    }

  private:
    void warn(std::ptrdiff_t offset, std::string message) {
        file_.warnings.push_back({json_.document().where(offset), std::move(message)});
    }
    void warn(const JsonValue& at, std::string message) { warn(at.offset, std::move(message)); }

    void read_profile(const JsonValue& at) {
        const auto name = json_.string(json_.member(at, "name"));
        for (const auto& member : at.members) {
            if (member.key != "name" && member.key != "feedbacks") {
                warn(member.key_offset,
                     "unknown member \"" + member.key + "\" of profile \"" + name + "\" ignored");
            }
        }
        const auto profile = parse_profile(name);
        if (!profile) {
            warn(*at.find("name"), "unknown profile \"" + name + "\" (feedbackd plays " +
                                       std::string(kProfileNames) +
                                       "): its feedbacks are never played");
            return;
        }
        if (file_.profiles.contains(*profile)) {
            warn(at, "profile \"" + name +
                         "\" given twice: the later one replaces the earlier, as in feedbackd");
        }
        auto& feedbacks = file_.profiles[*profile];
        feedbacks.clear();
        const JsonValue* list = at.find("feedbacks");
        if (list == nullptr) {
            return;
        }
        for (const auto& feedback : json_.array(*list).items) {
            const auto event = json_.string(json_.member(feedback, "event-name"));
            auto vibra = read_feedback(feedback, event);
            if (feedbacks.contains(event)) {
                warn(feedback, "a second feedback for \"" + event + "\" in profile \"" + name +
                                   "\": feedbackd keeps one per event and profile, the last");
            }
            feedbacks[event] = std::move(vibra);
        }
    }

    std::optional<VibraFeedback> read_feedback(const JsonValue& at, const std::string& event) {
        const JsonValue* type_at = at.find("type");
        if (type_at == nullptr) {
            warn(at, "the feedback for \"" + event + "\" has no \"type\": no vibration");
            return std::nullopt;
        }
        // feedbackd makes a class name of it, "FbdFeedback" + the type with its first letter
        // in capitals.
        std::string type = json_.string(*type_at);
        if (!type.empty()) {
            type[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(type[0])));
        }
        if (type == "Sound" || type == "Led" || type == "Dummy") {
            return std::nullopt;
        }
        if (type == "VibraRumble") {
            return rumble(at);
        }
        if (type == "VibraPeriodic") {
            return periodic(at);
        }
        if (type == "VibraPattern") {
            return pattern(at, event);
        }
        warn(*type_at, "unknown feedback type \"" + type +
                           "\" skipped (feedbackd 0.8.2 knows Sound, Led, Dummy, VibraRumble, "
                           "VibraPeriodic and VibraPattern)");
        return std::nullopt;
    }

    void unknown_members(const JsonValue& at, std::initializer_list<std::string_view> known,
                         std::string_view type) {
        for (const auto& member : at.members) {
            if (std::find(kVibraMembers.begin(), kVibraMembers.end(), member.key) ==
                    kVibraMembers.end() &&
                std::find(known.begin(), known.end(), member.key) == known.end()) {
                warn(member.key_offset, "unknown member \"" + member.key + "\" of a " +
                                            std::string(type) + " feedback ignored");
            }
        }
    }

    unsigned milliseconds(const JsonValue& at, const char* key, unsigned fallback) {
        const JsonValue* value = at.find(key);
        return value != nullptr ? static_cast<unsigned>(json_.integer(*value, 0, kMaxMs))
                                : fallback;
    }

    // A magnitude of feedbackd 0.8 (0..1). With `old_scale`, one above 1 is of 0.0.3's scale
    // and is converted; anything else outside 0..1 feedbackd refuses to set, keeping `fallback`.
    double magnitude(const JsonValue& at, const char* key, double fallback, bool old_scale) {
        const JsonValue* found = at.find(key);
        if (found == nullptr) {
            return fallback;
        }
        const double value = json_.number(*found);
        if (value >= 0.0 && value <= 1.0) {
            return value;
        }
        if (old_scale && value > 1.0) {
            const double converted = std::min(value / kOldScaleFull, 1.0);
            warn(*found, std::string(key) + " " + number_text(value) +
                             " is of feedbackd 0.0.3's scale (0 to 32767): read as " +
                             number_text(converted) +
                             " of full (feedbackd 0.8 divides by 65535); please update the "
                             "theme");
            return converted;
        }
        warn(*found, std::string(key) + " " + number_text(value) +
                         " is outside 0 to 1: feedbackd keeps its default, " +
                         number_text(fallback));
        return fallback;
    }

    VibraFeedback rumble(const JsonValue& at) {
        unknown_members(at, {"count", "pause", "magnitude"}, "VibraRumble");
        const JsonValue* count = at.find("count");
        return rumble_feedback(
            milliseconds(at, "duration", kDefaultVibraMs),
            count != nullptr ? static_cast<unsigned>(json_.integer(*count, 1, kMaxCount)) : 1,
            milliseconds(at, "pause", 0), magnitude(at, "magnitude", kDefaultMagnitude, false));
    }

    VibraFeedback periodic(const JsonValue& at) {
        unknown_members(at, {"magnitude", "fade-in-level", "fade-in-time"}, "VibraPeriodic");
        return periodic_feedback(milliseconds(at, "duration", kDefaultVibraMs),
                                 magnitude(at, "magnitude", kDefaultMagnitude, true),
                                 magnitude(at, "fade-in-level", 0.0, true),
                                 milliseconds(at, "fade-in-time", kDefaultFadeInMs));
    }

    std::optional<VibraFeedback> pattern(const JsonValue& at, const std::string& event) {
        unknown_members(at, {"magnitudes", "durations"}, "VibraPattern");
        if (const JsonValue* duration = at.find("duration")) {
            warn(*duration,
                 "a VibraPattern lasts as long as its durations together: "
                 "\"duration\" ignored");
        }
        const JsonValue* magnitudes = at.find("magnitudes");
        const JsonValue* durations = at.find("durations");
        if (magnitudes == nullptr || durations == nullptr) {
            warn(at, "the VibraPattern for \"" + event +
                         "\" lacks \"magnitudes\" or \"durations\": feedbackd plays nothing");
            return std::nullopt;
        }
        const auto& levels = json_.array(*magnitudes).items;
        const auto& lengths = json_.array(*durations).items;
        std::vector<VibraStep> steps;
        long long total = 0;
        for (std::size_t i = 0; i < std::min(levels.size(), lengths.size()); ++i) {
            double level = json_.number(levels[i]);
            if (level < 0.0 || level > 1.0) {
                const double clamped = std::clamp(level, 0.0, 1.0);
                warn(levels[i], "magnitude " + number_text(level) + " clamped to " +
                                    number_text(clamped) + ", as feedbackd clamps it");
                level = clamped;
            }
            const auto ms = json_.integer(lengths[i], 0, kMaxMs);
            total += ms;
            if (total > kMaxMs) {
                throw json_.error(lengths[i], "the pattern lasts longer than an hour (" +
                                                  std::to_string(kMaxMs) + " ms)");
            }
            steps.push_back({level, static_cast<unsigned>(ms)});
        }
        if (levels.size() != lengths.size()) {
            warn(at, "the VibraPattern for \"" + event + "\" has " + std::to_string(levels.size()) +
                         " magnitudes but " + std::to_string(lengths.size()) +
                         " durations: feedbackd plays nothing");
            return std::nullopt;
        }
        return pattern_feedback(std::move(steps));
    }

    const JsonFields& json_;
    FeedbackdThemeFile file_;
};

std::filesystem::path theme_file(const std::filesystem::path& dir, const std::string& name) {
    return dir / "feedbackd" / "themes" / (name + ".json");
}

bool file_exists(const std::filesystem::path& path) {
    std::error_code error;
    return std::filesystem::exists(path, error);
}

std::vector<std::filesystem::path> split_dirs(const char* value, const char* fallback) {
    const std::string text = value != nullptr && *value != '\0' ? value : fallback;
    std::vector<std::filesystem::path> dirs;
    std::size_t start = 0;
    for (;;) {
        const auto colon = text.find(':', start);
        const auto dir = text.substr(start, colon - start);
        if (!dir.empty()) {
            dirs.emplace_back(dir);
        }
        if (colon == std::string::npos) {
            return dirs;
        }
        start = colon + 1;
    }
}

}  // namespace

FeedbackdThemeFile read_feedbackd_theme_file(const JsonFields& json) {
    return FileReader(json).read();
}

ThemeSearch ThemeSearch::from_environment() {
    ThemeSearch search;
    const char* config = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    if (config != nullptr && *config != '\0') {
        search.config_home = config;
    } else if (home != nullptr && *home != '\0') {
        search.config_home = std::filesystem::path(home) / ".config";
    }
    search.data_dirs = split_dirs(std::getenv("XDG_DATA_DIRS"), "/usr/local/share:/usr/share");
    // The device tree's compatible strings, NUL-separated (gmobile reads them from here).
    std::ifstream in("/sys/firmware/devicetree/base/compatible", std::ios::binary);
    std::string compatible;
    while (std::getline(in, compatible, '\0')) {
        if (!compatible.empty()) {
            search.compatibles.push_back(compatible);
        }
    }
    return search;
}

std::filesystem::path ThemeSearch::find(const std::string& name, bool& device_theme_tried,
                                        std::vector<Diagnostic>& warnings) const {
    if (!config_home.empty() && file_exists(theme_file(config_home, name))) {
        return theme_file(config_home, name);
    }
    if ((name == "default" || name == "$device") && !device_theme_tried) {
        device_theme_tried = true;
        for (const auto& compatible : compatibles) {
            for (const auto& dir : data_dirs) {
                if (file_exists(theme_file(dir, compatible))) {
                    return theme_file(dir, compatible);
                }
            }
        }
    }
    if (name != "default") {
        warnings.push_back(
            {{}, "theme \"" + name + "\" not found, falling back to the default theme"});
    }
    for (const auto& dir : data_dirs) {
        if (file_exists(theme_file(dir, "default"))) {
            return theme_file(dir, "default");
        }
    }
    return builtin_dir / (name + ".json");
}

ThemeEntry vibra_entry(const std::string& event, VibraFeedback feedback) {
    ThemeEntry entry;
    entry.vibra = std::move(feedback);
    entry.usage = usage_for_event(event);
    return entry;
}

Theme expand_feedbackd_theme(FeedbackdThemeFile file, const ThemeSearch& search) {
    std::vector<FeedbackdThemeFile> chain;
    chain.push_back(std::move(file));
    std::vector<Diagnostic> search_warnings;
    bool device_theme_tried = false;
    for (std::size_t parents = 0;; ++parents) {
        const FeedbackdThemeFile& theme = chain.back();
        if (parents > kMaxParentThemes) {
            throw DocumentError(chain.front().parent_at,
                                "more than " + std::to_string(kMaxParentThemes) +
                                    " parent themes (feedbackd's limit): " + chain.front().path +
                                    " and then " + chain[1].path + " ... " + theme.path);
        }
        if (theme.name.empty()) {
            throw DocumentError(theme.name_at,
                                "a feedbackd theme needs a \"name\" that is not empty");
        }
        if (!theme.parent_name) {
            break;
        }
        if (theme.name == "default") {
            throw DocumentError(theme.parent_at, "the default theme cannot name a parent");
        }
        std::vector<Diagnostic> warnings;
        const auto parent = search.find(*theme.parent_name, device_theme_tried, warnings);
        for (auto& warning : warnings) {
            warning.where = theme.parent_at;
            search_warnings.push_back(std::move(warning));
        }
        const JsonDocument document = read_json_file(parent.string());
        if (document.root().kind == JsonValue::Kind::object &&
            document.root().find("vibscore-theme") != nullptr) {
            throw DocumentError({parent.string()},
                                "a parent theme must be a feedbackd theme, not vibscore's");
        }
        chain.push_back(read_feedbackd_theme_file(JsonFields(document)));
    }

    Theme theme;
    theme.name = chain.front().name;
    std::map<Profile, std::map<std::string, std::optional<VibraFeedback>>> merged;
    for (auto file = chain.rbegin(); file != chain.rend(); ++file) {
        for (auto& [profile, feedbacks] : file->profiles) {
            for (auto& [event, feedback] : feedbacks) {
                merged[profile][event] = std::move(feedback);
            }
        }
    }
    for (auto& [profile, feedbacks] : merged) {
        for (auto& [event, feedback] : feedbacks) {
            if (feedback) {
                theme.add(profile, event, vibra_entry(event, std::move(*feedback)));
            }
        }
    }
    for (auto& file : chain) {
        std::move(file.warnings.begin(), file.warnings.end(), std::back_inserter(theme.warnings));
    }
    std::move(search_warnings.begin(), search_warnings.end(), std::back_inserter(theme.warnings));
    return theme;
}

}  // namespace vibscore::feedback
