#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "score/document_error.hpp"
#include "score/line_index.hpp"

// The one JSON reader of the tree (the AHAP and Android importers, vibscore-feedback's themes
// and settings): a tree of values that remember where in the text each began, so a reader can
// name the file, line and column of a value that is wrong, not only of text that is not JSON.
// Reading is linear in the text and bounded: nesting deeper than max_depth is refused.
namespace vibscore {

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

struct JsonOptions {
    // Accept a comma before a closing bracket or brace ([1, 2,] and {"a": 1,}), as Apple's own
    // AHAP samples have it; trailing_commas() tells where they were.
    bool trailing_commas = false;
};

class JsonDocument {
  public:
    // Arrays and objects inside each other, the outermost counted as 1 (the AHAP and Android
    // readers' limit before this reader was shared).
    static constexpr std::size_t max_depth = 64;

    // Parses with nlohmann-json; text that is not JSON throws DocumentError at its line and
    // column, and so do nesting deeper than max_depth, a key given twice in one object and a
    // number too large for a double (1e999).
    JsonDocument(std::string_view text, std::string file, JsonOptions options = {});

    const JsonValue& root() const { return root_; }
    SourceLocation where(const JsonValue& value) const { return lines_.at(value.offset); }
    SourceLocation where(std::ptrdiff_t offset) const { return lines_.at(offset); }
    const std::string& file() const { return lines_.file(); }
    // Offsets of the trailing commas JsonOptions::trailing_commas let through, in text order.
    const std::vector<std::ptrdiff_t>& trailing_commas() const { return trailing_commas_; }

  private:
    LineIndex lines_;
    JsonValue root_;
    std::vector<std::ptrdiff_t> trailing_commas_;
};

// A JSON file of at most max_json_file_bytes. Throws DocumentError naming the file when it
// cannot be read or is too large, and at the place where its text is wrong.
inline constexpr std::size_t max_json_file_bytes = 1 << 20;
JsonDocument read_json_file(const std::string& path, JsonOptions options = {});

}  // namespace vibscore
