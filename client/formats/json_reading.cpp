#include "client/formats/json_reading.hpp"

#include <algorithm>
#include <cmath>

#include "score/xml_support.hpp"

namespace vibscore::formats {

bool JsonReader::expect(const JsonValue& value, JsonValue::Kind kind, std::string_view what) const {
    if (value.kind == kind) {
        return true;
    }
    report(value, std::string(what) + " must be " + std::string(to_string(kind)) + ", not " +
                      std::string(to_string(value.kind)));
    return false;
}

void JsonReader::check_keys(const JsonValue& object, std::initializer_list<std::string_view> known,
                            std::string_view what) const {
    for (const auto& member : object.members) {
        if (std::find(known.begin(), known.end(), member.key) == known.end()) {
            std::string expected;
            for (const auto key : known) {
                expected += (expected.empty() ? "" : ", ") + std::string(key);
            }
            sink_.report(document_.where(member.key_offset), "unknown key \"" + member.key +
                                                                 "\" in " + std::string(what) +
                                                                 " (expected " + expected + ")");
        }
    }
}

const JsonValue* JsonReader::member(const JsonValue& object, std::string_view key,
                                    std::string_view what) const {
    const JsonValue* found = object.find(key);
    if (found == nullptr) {
        report(object, std::string(what) + " has no \"" + std::string(key) + "\"");
    }
    return found;
}

std::optional<double> JsonReader::number(const JsonValue& value, std::string_view what, double min,
                                         double max) const {
    if (!expect(value, JsonValue::Kind::number, what)) {
        return std::nullopt;
    }
    if (!std::isfinite(value.number) || value.number < min || value.number > max) {
        report(value, std::string(what) + " " + xml::format_number(value.number) +
                          " is out of range (" + xml::format_number(min) + " to " +
                          xml::format_number(max) + ")");
        return std::nullopt;
    }
    return value.number;
}

std::optional<long long> JsonReader::integer(const JsonValue& value, std::string_view what,
                                             long long min, long long max) const {
    const auto read = number(value, what, static_cast<double>(min), static_cast<double>(max));
    if (!read) {
        return std::nullopt;
    }
    if (!value.integral) {
        report(value,
               std::string(what) + " must be a whole number, not " + xml::format_number(*read));
        return std::nullopt;
    }
    return static_cast<long long>(*read);
}

std::optional<std::string> JsonReader::string(const JsonValue& value, std::string_view what) const {
    if (!expect(value, JsonValue::Kind::string, what)) {
        return std::nullopt;
    }
    return value.text;
}

}  // namespace vibscore::formats
