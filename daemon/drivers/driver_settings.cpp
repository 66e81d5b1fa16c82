#include "daemon/drivers/driver_settings.hpp"

#include <charconv>
#include <cmath>
#include <utility>
#include <vector>

#include "common/closest_name.hpp"
#include "common/ini_reader.hpp"
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"

namespace vibscore::drivers {

DriverSettings::DriverSettings(std::string driver, std::map<std::string, std::string> settings)
    : driver_(std::move(driver)), settings_(std::move(settings)) {}

bool DriverSettings::has(const std::string& key) const {
    return settings_.count(key) != 0;
}

const std::string* DriverSettings::lookup(const std::string& key) {
    asked_.insert(key);
    const auto found = settings_.find(key);
    return found == settings_.end() ? nullptr : &found->second;
}

SettingError DriverSettings::bad(const std::string& key, const std::string& value,
                                 const std::string& expected) const {
    return SettingError(key, driver_ + " setting " + shown_text(key) + " = " + quoted_text(value) +
                                 ": expected " + expected);
}

std::optional<std::string> DriverSettings::text(const std::string& key) {
    const std::string* value = lookup(key);
    if (!value) {
        return std::nullopt;
    }
    if (value->empty()) {
        throw bad(key, *value, "a value");
    }
    return *value;
}

std::string DriverSettings::text(const std::string& key, const std::string& fallback) {
    return text(key).value_or(fallback);
}

std::optional<double> DriverSettings::number(const std::string& key, double min, double max) {
    const std::string* value = lookup(key);
    if (!value) {
        return std::nullopt;
    }
    const auto number = ini_number(*value);
    if (!number || *number < min || *number > max) {
        throw bad(key, *value, "a number from " + number_text(min) + " to " + number_text(max));
    }
    return *number;
}

double DriverSettings::number(const std::string& key, double fallback, double min, double max) {
    return number(key, min, max).value_or(fallback);
}

std::optional<long> DriverSettings::integer(const std::string& key, long min, long max) {
    const std::string* value = lookup(key);
    if (!value) {
        return std::nullopt;
    }
    long number = 0;
    const char* const end = value->data() + value->size();
    const auto [ptr, error] = std::from_chars(value->data(), end, number);
    if (error != std::errc{} || ptr != end || number < min || number > max) {
        throw bad(key, *value,
                  "a whole number from " + std::to_string(min) + " to " + std::to_string(max));
    }
    return number;
}

long DriverSettings::integer(const std::string& key, long fallback, long min, long max) {
    return integer(key, min, max).value_or(fallback);
}

bool DriverSettings::flag(const std::string& key, bool fallback) {
    const std::string* value = lookup(key);
    if (!value) {
        return fallback;
    }
    if (*value == "true") {
        return true;
    }
    if (*value == "false") {
        return false;
    }
    throw bad(key, *value, "true or false");
}

std::string DriverSettings::choice(const std::string& key, const std::string& fallback,
                                   std::initializer_list<const char*> allowed) {
    const std::string* value = lookup(key);
    if (!value) {
        return fallback;
    }
    std::string names;
    for (const char* option : allowed) {
        if (*value == option) {
            return *value;
        }
        names += (names.empty() ? "" : " or ") + std::string(option);
    }
    throw bad(key, *value, names);
}

SettingError DriverSettings::unknown(const std::string& key, const std::string& value) const {
    std::set<std::string> known(asked_);
    known.insert(std::begin(kCommonSettingKeys), std::end(kCommonSettingKeys));
    std::string list;
    for (const auto& name : known) {
        list += (list.empty() ? "" : ", ") + name;
    }
    const auto meant = closest_name(key, std::vector<std::string>(known.begin(), known.end()));
    return SettingError(
        key, "unknown " + driver_ + " setting " + shown_text(key) + " = " + quoted_text(value) +
                 (meant ? " (did you mean " + *meant + "?)" : "") + " (known: " + list + ")");
}

SettingError DriverSettings::missing(const std::string& key, const std::string& what) {
    asked_.insert(key);
    // "lines = 17" without "line": the typo is the mistake to report, not the missing key.
    for (const auto& [present, value] : settings_) {
        if (asked_.count(present) == 0 && closest_name(present, {key}) == key) {
            return unknown(present, value);
        }
    }
    return SettingError(key, driver_ + " setting " + key + " is missing: " + what);
}

void DriverSettings::reject_unknown() const {
    for (const auto& [key, value] : settings_) {
        if (asked_.count(key) == 0) {
            throw unknown(key, value);
        }
    }
}

}  // namespace vibscore::drivers
