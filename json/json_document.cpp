#include "json/json_document.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <unordered_set>

namespace vibscore {

namespace {

constexpr int kNumberOverflow = 406;  // nlohmann's out_of_range.406: a number beyond a double

bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// The text with each trailing comma ([1,] or {"a": 1,}) turned into a blank, so every other
// character keeps its offset; `found` gets where they were. One pass: strings are skipped with
// their escapes, and a comma counts only after a value (so [,] and [1,,] stay errors).
std::string blank_trailing_commas(std::string_view text, std::vector<std::ptrdiff_t>& found) {
    std::string out(text);
    char last = '\0';  // the last character outside blanks and strings, '"' after a string
    for (std::size_t i = 0; i < out.size(); ++i) {
        const char c = out[i];
        if (c == '"') {
            for (++i; i < out.size() && out[i] != '"'; ++i) {
                i += out[i] == '\\' ? 1 : 0;
            }
            last = '"';
            continue;
        }
        if (is_blank(c)) {
            continue;
        }
        if (c == ',' && last != '\0' && std::strchr("[{,:", last) == nullptr) {
            std::size_t next = i + 1;
            while (next < out.size() && is_blank(out[next])) {
                ++next;
            }
            if (next < out.size() && (out[next] == ']' || out[next] == '}')) {
                out[i] = ' ';
                found.push_back(static_cast<std::ptrdiff_t>(i));
                continue;  // `last` stays the value before it
            }
        }
        last = c;
    }
    return out;
}

// Walks the text for nlohmann's parser and leaves behind how far it has read: each SAX event
// then knows where the token it reports ended, and so where the value began.
class ReadingIterator {
  public:
    using iterator_category = std::input_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = const char&;

    ReadingIterator(const char* at, const char** reached) : at_(at), reached_(reached) {}
    reference operator*() const { return *at_; }
    ReadingIterator& operator++() {
        *reached_ = ++at_;
        return *this;
    }
    ReadingIterator operator++(int) {
        auto before = *this;
        ++*this;
        return before;
    }
    bool operator==(const ReadingIterator& other) const { return at_ == other.at_; }

  private:
    const char* at_;
    const char** reached_;
};

class TreeBuilder : public nlohmann::json_sax<nlohmann::json> {
  public:
    TreeBuilder(std::string_view text, const LineIndex& lines, JsonValue& root)
        : text_(text), lines_(lines), root_(root), reached_(text.data()), last_end_(text.data()) {}

    const char** reached() { return &reached_; }

    bool null() override {
        add(JsonValue::Kind::null);
        return true;
    }
    bool boolean(bool value) override {
        add(JsonValue::Kind::boolean).boolean = value;
        return true;
    }
    bool number_integer(number_integer_t value) override {
        auto& added = add(JsonValue::Kind::number);
        added.number = static_cast<double>(value);
        added.integral = true;
        return true;
    }
    bool number_unsigned(number_unsigned_t value) override {
        auto& added = add(JsonValue::Kind::number);
        added.number = static_cast<double>(value);
        added.integral = true;
        return true;
    }
    bool number_float(number_float_t value, const string_t&) override {
        add(JsonValue::Kind::number).number = value;
        return true;
    }
    bool string(string_t& value) override {
        add(JsonValue::Kind::string).text = std::move(value);
        return true;
    }
    bool binary(binary_t&) override {
        add(JsonValue::Kind::null);  // only CBOR and the like have binary values
        return true;
    }
    bool start_object(std::size_t) override { return open(JsonValue::Kind::object); }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(JsonValue::Kind::array); }
    bool end_array() override { return close(); }
    bool key(string_t& value) override {
        const auto offset = token_start();
        auto& frame = open_.back();
        // A set per open object keeps the check linear in the number of keys.
        if (!frame.keys.insert(value).second) {
            throw DocumentError(lines_.at(offset),
                                "key \"" + value + "\" appears twice in one object");
        }
        frame.value->members.push_back({std::move(value), offset, {}});
        return true;
    }
    bool parse_error(std::size_t position, const std::string& last_token,
                     const nlohmann::detail::exception& error) override {
        std::string message = error.what();
        // Point at the token at fault. nlohmann's position is just past the character it
        // stopped at: for a bracket, brace, colon or comma where none may stand ("unexpected
        // ','") that character is the token; for a string, number or literal the token began
        // after the last one read well.
        const bool separator = message.find("unexpected '") != std::string::npos && position > 0;
        const auto where =
            lines_.at(separator ? static_cast<std::ptrdiff_t>(std::min(position, text_.size()) - 1)
                                : token_start());
        if (error.id == kNumberOverflow) {
            throw DocumentError(where, "number " + last_token + " is too large");
        }
        // nlohmann prefixes "[json.exception...] parse error at line L, column C: "; the
        // location is ours to give.
        if (const auto column = message.find("column "); column != std::string::npos) {
            if (const auto colon = message.find(": ", column); colon != std::string::npos) {
                message = message.substr(colon + 2);
            }
        } else if (const auto bracket = message.find("] "); bracket != std::string::npos) {
            message = message.substr(bracket + 2);
        }
        throw DocumentError(where, "not JSON: " + message);
    }

  private:
    // Where the token just read began: after the previous token, past blanks and separators.
    std::ptrdiff_t token_start() {
        const char* at = last_end_;
        const char* end = text_.data() + text_.size();
        while (at < end && (*at == ' ' || *at == '\t' || *at == '\n' || *at == '\r' || *at == ',' ||
                            *at == ':')) {
            ++at;
        }
        last_end_ = reached_;
        return at - text_.data();
    }

    JsonValue& add(JsonValue::Kind kind) {
        JsonValue value;
        value.kind = kind;
        value.offset = token_start();
        if (open_.empty()) {
            root_ = std::move(value);
            return root_;
        }
        auto& parent = *open_.back().value;
        if (parent.kind == JsonValue::Kind::array) {
            parent.items.push_back(std::move(value));
            return parent.items.back();
        }
        parent.members.back().value = std::move(value);
        return parent.members.back().value;
    }
    bool open(JsonValue::Kind kind) {
        if (open_.size() >= JsonDocument::max_depth) {
            throw DocumentError(
                lines_.at(token_start()),
                "nested deeper than " + std::to_string(JsonDocument::max_depth) + " levels");
        }
        open_.push_back({&add(kind), {}});
        return true;
    }
    bool close() {
        last_end_ = reached_;
        open_.pop_back();
        return true;
    }

    std::string_view text_;
    const LineIndex& lines_;
    JsonValue& root_;
    const char* reached_;
    const char* last_end_;
    // The arrays and objects being read, outermost first. A pointer stays valid: only the
    // innermost one grows.
    struct Frame {
        JsonValue* value;
        std::unordered_set<std::string> keys;  // an object's keys so far
    };
    std::vector<Frame> open_;
};

}  // namespace

const JsonValue* JsonValue::find(std::string_view key) const {
    for (const auto& member : members) {
        if (member.key == key) {
            return &member.value;
        }
    }
    return nullptr;
}

std::string_view to_string(JsonValue::Kind kind) {
    switch (kind) {
        case JsonValue::Kind::null:
            return "null";
        case JsonValue::Kind::boolean:
            return "a boolean";
        case JsonValue::Kind::number:
            return "a number";
        case JsonValue::Kind::string:
            return "a string";
        case JsonValue::Kind::array:
            return "an array";
        case JsonValue::Kind::object:
            return "an object";
    }
    return "?";
}

JsonDocument::JsonDocument(std::string_view text, std::string file, JsonOptions options)
    : lines_(text, std::move(file)) {
    // nlohmann's words for this differ between its releases (Debian 12's and 13's): ours.
    if (std::all_of(text.begin(), text.end(), is_blank)) {
        throw DocumentError(lines_.at(static_cast<std::ptrdiff_t>(text.size())),
                            "not JSON: the text is empty");
    }
    std::string tolerant;
    if (options.trailing_commas) {
        tolerant = blank_trailing_commas(text, trailing_commas_);
        text = tolerant;
    }
    TreeBuilder builder(text, lines_, root_);
    const ReadingIterator first(text.data(), builder.reached());
    const ReadingIterator last(text.data() + text.size(), builder.reached());
    nlohmann::json::sax_parse(first, last, &builder);
}

JsonDocument read_json_file(const std::string& path, JsonOptions options) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw DocumentError({path}, std::string("cannot open: ") + std::strerror(errno));
    }
    std::string text(max_json_file_bytes + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    if (in.bad()) {
        throw DocumentError({path}, std::string("cannot read: ") + std::strerror(errno));
    }
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_json_file_bytes) {
        throw DocumentError({path}, "larger than " + std::to_string(max_json_file_bytes) +
                                        " bytes, the limit for a JSON file");
    }
    return JsonDocument(text, path, options);
}

}  // namespace vibscore
