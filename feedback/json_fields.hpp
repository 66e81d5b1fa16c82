#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

#include "json/json_document.hpp"
#include "score/document_error.hpp"

// Typed reading of a theme's or settings file's JSON for vibscore-feedback: each accessor
// returns the value asked for or throws DocumentError "file:line:column: what" at the value at
// fault (at the object, for a member that is missing). vibscore-feedback stops at the first
// error: a theme that does not read is not served.
namespace vibscore::feedback {

class JsonFields {
  public:
    explicit JsonFields(const JsonDocument& document) : document_(document) {}

    const JsonDocument& document() const { return document_; }
    SourceLocation where(const JsonValue& value) const { return document_.where(value); }
    DocumentError error(const JsonValue& at, const std::string& message) const;
    // The member `key` of `object`; missing, an error at the object.
    const JsonValue& member(const JsonValue& object, std::string_view key) const;

    const JsonValue& object(const JsonValue& value) const;
    const JsonValue& array(const JsonValue& value) const;
    std::string string(const JsonValue& value) const;
    bool boolean(const JsonValue& value) const;
    double number(const JsonValue& value) const;
    // A number in [min, max].
    double number(const JsonValue& value, double min, double max) const;
    // A whole number (no fraction or exponent) in [min, max].
    long long integer(const JsonValue& value, long long min, long long max) const;
    // Refuses members of `object` not named in `known`.
    void only_members(const JsonValue& object, std::initializer_list<std::string_view> known) const;

  private:
    const JsonDocument& document_;
};

// A value as an error message quotes it: 1.5, "loud", true, null, an array, an object.
std::string describe(const JsonValue& value);
// "a, b or c".
std::string join_names(std::initializer_list<std::string_view> names);

}  // namespace vibscore::feedback
