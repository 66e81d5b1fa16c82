#include "feedback/json_document.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

namespace vibscore::feedback {

namespace {

constexpr std::size_t kMaxFileBytes = 1 << 20;

// Walks a text nlohmann::json has accepted and notes where every value begins, by JSON pointer.
// The text is known to be valid JSON, so the walk needs no error handling of its own.
class ValueLocator {
  public:
    ValueLocator(std::string_view text, std::map<std::string, std::size_t>& offsets)
        : text_(text), offsets_(offsets), i_(text.starts_with("\xEF\xBB\xBF") ? 3 : 0) {}

    void value(const nlohmann::json::json_pointer& at) {
        skip_space();
        offsets_[at.to_string()] = i_;
        switch (text_[i_]) {
            case '{':
                members(at);
                break;
            case '[':
                elements(at);
                break;
            case '"':
                string();
                break;
            default:
                while (i_ < text_.size() && std::strchr(",}] \t\r\n", text_[i_]) == nullptr) {
                    ++i_;
                }
        }
    }

  private:
    void skip_space() {
        while (i_ < text_.size() && std::strchr(" \t\r\n", text_[i_]) != nullptr) {
            ++i_;
        }
    }
    // Past a string token; returns it decoded (escapes included) by the JSON library itself.
    std::string string() {
        const std::size_t start = i_++;
        while (text_[i_] != '"') {
            i_ += text_[i_] == '\\' ? 2 : 1;
        }
        ++i_;
        return nlohmann::json::parse(text_.substr(start, i_ - start)).get<std::string>();
    }
    void members(const nlohmann::json::json_pointer& at) {
        ++i_;
        skip_space();
        if (text_[i_] == '}') {
            ++i_;
            return;
        }
        for (;;) {
            skip_space();
            const std::string key = string();
            skip_space();
            ++i_;  // ':'
            value(at / key);
            skip_space();
            if (text_[i_++] == '}') {
                return;
            }
        }
    }
    void elements(const nlohmann::json::json_pointer& at) {
        ++i_;
        skip_space();
        if (text_[i_] == ']') {
            ++i_;
            return;
        }
        for (std::size_t index = 0;; ++index) {
            value(at / index);
            skip_space();
            if (text_[i_++] == ']') {
                return;
            }
        }
    }

    std::string_view text_;
    std::map<std::string, std::size_t>& offsets_;
    std::size_t i_;  // past a UTF-8 byte order mark, which the JSON library skips too
};

// nlohmann's own message after its "[json.exception.parse_error.101] parse error at line L,
// column C: " prefix, which this file's own position replaces.
std::string parse_error_text(const std::string& what) {
    const auto column = what.find("column ");
    const auto colon = column == std::string::npos ? column : what.find(": ", column);
    return colon == std::string::npos ? what : what.substr(colon + 2);
}

}  // namespace

JsonDocument::JsonDocument(std::string_view text, std::string file) : file_(std::move(file)) {
    line_starts_.push_back(0);
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\n') {
            line_starts_.push_back(i + 1);
        }
    }
    try {
        root_ = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& error) {
        // error.byte counts from 1 and is the character at which parsing failed.
        const std::size_t offset = error.byte > 0 ? error.byte - 1 : 0;
        throw JsonError(location(std::min(offset, text.size())) + ": " +
                        parse_error_text(error.what()));
    }
    ValueLocator(text, offsets_).value(nlohmann::json::json_pointer());
}

std::string JsonDocument::location(std::size_t offset) const {
    const auto line = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset) - 1;
    return file_ + ":" + std::to_string(line - line_starts_.begin() + 1) + ":" +
           std::to_string(offset - *line + 1);
}

std::string JsonDocument::where(const nlohmann::json::json_pointer& at) const {
    const auto found = offsets_.find(at.to_string());
    return found == offsets_.end() ? file_ : location(found->second);
}

JsonError JsonDocument::error(const nlohmann::json::json_pointer& at,
                              const std::string& message) const {
    return JsonError(where(at) + ": " + message);
}

const nlohmann::json& JsonDocument::value(const nlohmann::json::json_pointer& at) const {
    if (!root_.contains(at)) {
        const std::string& name = at.back();
        throw error(at.parent_pointer(), "missing \"" + name + "\"");
    }
    return root_.at(at);
}

const nlohmann::json& JsonDocument::object(const nlohmann::json::json_pointer& at) const {
    const auto& found = value(at);
    if (!found.is_object()) {
        throw error(at, "expected an object ({...}), found " + found.dump());
    }
    return found;
}

const nlohmann::json& JsonDocument::array(const nlohmann::json::json_pointer& at) const {
    const auto& found = value(at);
    if (!found.is_array()) {
        throw error(at, "expected an array ([...]), found " + found.dump());
    }
    return found;
}

std::string JsonDocument::string(const nlohmann::json::json_pointer& at) const {
    const auto& found = value(at);
    if (!found.is_string()) {
        throw error(at, "expected a string, found " + found.dump());
    }
    return found.get<std::string>();
}

double JsonDocument::number(const nlohmann::json::json_pointer& at, double min, double max) const {
    const auto& found = value(at);
    if (!found.is_number() || !(found.get<double>() >= min && found.get<double>() <= max)) {
        throw error(at, "expected a number from " + nlohmann::json(min).dump() + " to " +
                            nlohmann::json(max).dump() + ", found " + found.dump());
    }
    return found.get<double>();
}

long JsonDocument::integer(const nlohmann::json::json_pointer& at, long min, long max) const {
    const auto& found = value(at);
    if (!found.is_number_integer() || found.get<long>() < min || found.get<long>() > max) {
        throw error(at, "expected a whole number from " + std::to_string(min) + " to " +
                            std::to_string(max) + ", found " + found.dump());
    }
    return found.get<long>();
}

void JsonDocument::only_members(const nlohmann::json::json_pointer& at,
                                std::initializer_list<std::string_view> known) const {
    for (const auto& [key, member] : object(at).items()) {
        if (std::find(known.begin(), known.end(), key) == known.end()) {
            std::string names;
            for (const auto name : known) {
                names += (names.empty() ? "" : ", ") + std::string(name);
            }
            throw error(at / key, "unknown member \"" + key + "\" (expected " + names + ")");
        }
    }
}

JsonDocument read_json_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw JsonError(path + ": cannot open: " + std::strerror(errno));
    }
    std::string text;
    text.resize(kMaxFileBytes + 1);
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxFileBytes) {
        throw JsonError(path + ": larger than " + std::to_string(kMaxFileBytes) + " bytes");
    }
    return JsonDocument(text, path);
}

}  // namespace vibscore::feedback
