#include "feedback/json_fields.hpp"

#include <algorithm>

#include "common/number_text.hpp"

namespace vibscore::feedback {

std::string describe(const JsonValue& value) {
    switch (value.kind) {
        case JsonValue::Kind::null:
            return "null";
        case JsonValue::Kind::boolean:
            return value.boolean ? "true" : "false";
        case JsonValue::Kind::number:
            return number_text(value.number);
        case JsonValue::Kind::string:
            return "\"" + value.text + "\"";
        case JsonValue::Kind::array:
        case JsonValue::Kind::object:
            break;
    }
    return std::string(to_string(value.kind));
}

std::string join_names(std::initializer_list<std::string_view> names) {
    std::string text;
    std::size_t i = 0;
    for (const auto name : names) {
        text += i == 0 ? "" : (i + 1 == names.size() ? " or " : ", ");
        text += name;
        ++i;
    }
    return text;
}

DocumentError JsonFields::error(const JsonValue& at, const std::string& message) const {
    return DocumentError(document_.where(at), message);
}

const JsonValue& JsonFields::member(const JsonValue& object, std::string_view key) const {
    const JsonValue* found = this->object(object).find(key);
    if (found == nullptr) {
        throw error(object, "missing \"" + std::string(key) + "\"");
    }
    return *found;
}

const JsonValue& JsonFields::object(const JsonValue& value) const {
    if (value.kind != JsonValue::Kind::object) {
        throw error(value, "expected an object ({...}), found " + describe(value));
    }
    return value;
}

const JsonValue& JsonFields::array(const JsonValue& value) const {
    if (value.kind != JsonValue::Kind::array) {
        throw error(value, "expected an array ([...]), found " + describe(value));
    }
    return value;
}

std::string JsonFields::string(const JsonValue& value) const {
    if (value.kind != JsonValue::Kind::string) {
        throw error(value, "expected a string, found " + describe(value));
    }
    return value.text;
}

bool JsonFields::boolean(const JsonValue& value) const {
    if (value.kind != JsonValue::Kind::boolean) {
        throw error(value, "expected true or false, found " + describe(value));
    }
    return value.boolean;
}

double JsonFields::number(const JsonValue& value) const {
    if (value.kind != JsonValue::Kind::number) {
        throw error(value, "expected a number, found " + describe(value));
    }
    return value.number;
}

double JsonFields::number(const JsonValue& value, double min, double max) const {
    if (value.kind != JsonValue::Kind::number || !(value.number >= min && value.number <= max)) {
        throw error(value, "expected a number from " + number_text(min) + " to " +
                               number_text(max) + ", found " + describe(value));
    }
    return value.number;
}

long long JsonFields::integer(const JsonValue& value, long long min, long long max) const {
    if (value.kind != JsonValue::Kind::number || !value.integral ||
        !(value.number >= static_cast<double>(min) && value.number <= static_cast<double>(max))) {
        throw error(value, "expected a whole number from " + std::to_string(min) + " to " +
                               std::to_string(max) + ", found " + describe(value));
    }
    return static_cast<long long>(value.number);
}

void JsonFields::only_members(const JsonValue& object,
                              std::initializer_list<std::string_view> known) const {
    for (const auto& member : this->object(object).members) {
        if (std::find(known.begin(), known.end(), member.key) == known.end()) {
            throw DocumentError(
                document_.where(member.key_offset),
                "unknown member \"" + member.key + "\" (expected " + join_names(known) + ")");
        }
    }
}

}  // namespace vibscore::feedback
