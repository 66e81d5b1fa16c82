#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "score/document_error.hpp"
#include "score/line_index.hpp"

namespace vibscore::formats {

// A JSON value that remembers where in its text it began, so readers can name the line and
// column of a value that is wrong, not only of text that is not JSON at all.
struct JsonValue {
    enum class Kind { null, boolean, number, string, array, object };
    struct Member;

    Kind kind = Kind::null;
    std::ptrdiff_t offset = 0;  // byte offset of its first character
    bool boolean = false;
    double number = 0.0;
    bool integral = false;  // written without fraction or exponent
    std::string text;       // a string's value
    std::vector<JsonValue> items;
    std::vector<Member> members;  // in document order

    const JsonValue* find(std::string_view key) const;
};

struct JsonValue::Member {
    std::string key;
    std::ptrdiff_t key_offset = 0;
    JsonValue value;
};

std::string_view to_string(JsonValue::Kind kind);

class JsonDocument {
  public:
    // Parses with nlohmann-json; text that is not JSON throws DocumentError at its line and
    // column, and so do nesting deeper than 64 levels and a key given twice in one object.
    JsonDocument(std::string_view text, std::string file);

    const JsonValue& root() const { return root_; }
    SourceLocation where(const JsonValue& value) const { return lines_.at(value.offset); }
    SourceLocation where(std::ptrdiff_t offset) const { return lines_.at(offset); }
    const std::string& file() const { return lines_.file(); }

  private:
    LineIndex lines_;
    JsonValue root_;
};

}  // namespace vibscore::formats
