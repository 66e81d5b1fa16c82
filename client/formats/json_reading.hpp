#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "json/json_document.hpp"
#include "score/document_error.hpp"

namespace vibscore::formats {

// Strict readers of JSON values that report what is wrong, and where, to a sink.
class JsonReader {
  public:
    JsonReader(const JsonDocument& document, DiagnosticSink& sink)
        : document_(document), sink_(sink) {}

    void report(const JsonValue& at, const std::string& message) const {
        sink_.report(document_.where(at), message);
    }
    // The value is of this kind, or a problem is reported.
    bool expect(const JsonValue& value, JsonValue::Kind kind, std::string_view what) const;
    // Reports every key of `object` not in `known`.
    void check_keys(const JsonValue& object, std::initializer_list<std::string_view> known,
                    std::string_view what) const;
    // A required member; reports its absence at the object.
    const JsonValue* member(const JsonValue& object, std::string_view key,
                            std::string_view what) const;
    // A finite number in [min, max].
    std::optional<double> number(const JsonValue& value, std::string_view what, double min,
                                 double max) const;
    // A whole number in [min, max].
    std::optional<long long> integer(const JsonValue& value, std::string_view what, long long min,
                                     long long max) const;
    std::optional<std::string> string(const JsonValue& value, std::string_view what) const;

  private:
    const JsonDocument& document_;
    DiagnosticSink& sink_;
};

}  // namespace vibscore::formats
