#pragma once

#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace vibscore::drivers {

// The keys every backend takes besides its own (configured_actuator.hpp); the player enforces them.
inline constexpr const char* kCommonSettingKeys[] = {"max-on-time-ms", "pulse-period-ms"};

// A setting the backend refuses; key() lets the configuration name the file and line it came from.
class SettingError : public std::invalid_argument {
  public:
    SettingError(std::string key, const std::string& message)
        : std::invalid_argument(message), key_(std::move(key)) {}
    const std::string& key() const { return key_; }

  private:
    std::string key_;
};

// Reads one driver's "key = value" settings (its section of vibscored.conf) with typed
// accessors. Every error is a SettingError naming the driver, key and value, e.g.
//   evdev setting carrier-hz = "fast": expected a number from 10 to 20000
// Drivers call reject_unknown() last, so a misspelt key is an error, not a silent default.
class DriverSettings {
  public:
    DriverSettings(std::string driver, std::map<std::string, std::string> settings);

    const std::string& driver() const { return driver_; }
    bool has(const std::string& key) const;

    std::optional<std::string> text(const std::string& key);
    std::string text(const std::string& key, const std::string& fallback);
    double number(const std::string& key, double fallback, double min, double max);
    std::optional<double> number(const std::string& key, double min, double max);
    long integer(const std::string& key, long fallback, long min, long max);
    std::optional<long> integer(const std::string& key, long min, long max);
    bool flag(const std::string& key, bool fallback);
    std::string choice(const std::string& key, const std::string& fallback,
                       std::initializer_list<const char*> allowed);

    // Throws for any setting none of the accessors above asked for, naming the known key it
    // most likely misspells and listing the known keys (the common ones too).
    void reject_unknown() const;

    // The error for a required `key` that is not set ("... is missing: <what>"), unless a key
    // that is set misspells it: then that one is the error, as reject_unknown() words it.
    SettingError missing(const std::string& key, const std::string& what);

  private:
    const std::string* lookup(const std::string& key);
    SettingError bad(const std::string& key, const std::string& value,
                     const std::string& expected) const;
    SettingError unknown(const std::string& key, const std::string& value) const;

    std::string driver_;
    std::map<std::string, std::string> settings_;
    std::set<std::string> asked_;
};

}  // namespace vibscore::drivers
