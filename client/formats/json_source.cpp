#include "client/formats/json_source.hpp"

#include <nlohmann/json.hpp>

#include <iterator>

namespace vibscore::formats {

namespace {

constexpr std::size_t kMaxDepth = 64;

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
        auto& object = *open_.back();
        for (const auto& member : object.members) {
            if (member.key == value) {
                throw DocumentError(lines_.at(offset),
                                    "key \"" + value + "\" appears twice in one object");
            }
        }
        object.members.push_back({std::move(value), offset, {}});
        return true;
    }
    bool parse_error(std::size_t, const std::string&,
                     const nlohmann::detail::exception& error) override {
        std::string message = error.what();
        // nlohmann prefixes "[json.exception...] parse error at line L, column C: "; the
        // location is ours to give.
        if (const auto column = message.find("column "); column != std::string::npos) {
            if (const auto colon = message.find(": ", column); colon != std::string::npos) {
                message = message.substr(colon + 2);
            }
        }
        // nlohmann's position is where it stopped reading, past the token at fault; point at
        // the token's start instead.
        throw DocumentError(lines_.at(token_start()), "not JSON: " + message);
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
        auto& parent = *open_.back();
        if (parent.kind == JsonValue::Kind::array) {
            parent.items.push_back(std::move(value));
            return parent.items.back();
        }
        parent.members.back().value = std::move(value);
        return parent.members.back().value;
    }
    bool open(JsonValue::Kind kind) {
        if (open_.size() >= kMaxDepth) {
            throw DocumentError(lines_.at(token_start()),
                                "nested deeper than " + std::to_string(kMaxDepth) + " levels");
        }
        open_.push_back(&add(kind));
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
    std::vector<JsonValue*> open_;
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

JsonDocument::JsonDocument(std::string_view text, std::string file)
    : lines_(text, std::move(file)) {
    TreeBuilder builder(text, lines_, root_);
    const ReadingIterator first(text.data(), builder.reached());
    const ReadingIterator last(text.data() + text.size(), builder.reached());
    nlohmann::json::sax_parse(first, last, &builder);
}

}  // namespace vibscore::formats
