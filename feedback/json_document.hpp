#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vibscore::feedback {

// A JSON file is wrong: the message is "file:line:column: what", as score documents report.
class JsonError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A parsed JSON text that still knows where each value stood, so a reader that finds a value
// wrong can name its line and column, not only its path.
class JsonDocument {
  public:
    // Throws JsonError at the place the text stops being JSON.
    JsonDocument(std::string_view text, std::string file);

    const nlohmann::json& root() const { return root_; }
    const std::string& file() const { return file_; }

    // "file:line:column" of the first character of the value at `at` (the file alone when the
    // document has no such value).
    std::string where(const nlohmann::json::json_pointer& at) const;
    // A JsonError for the value at `at`.
    JsonError error(const nlohmann::json::json_pointer& at, const std::string& message) const;

    // Typed access for readers: each throws a JsonError naming the place when the value is
    // missing (at its parent) or of another kind or range (at the value).
    bool has(const nlohmann::json::json_pointer& at) const { return root_.contains(at); }
    const nlohmann::json& object(const nlohmann::json::json_pointer& at) const;
    const nlohmann::json& array(const nlohmann::json::json_pointer& at) const;
    std::string string(const nlohmann::json::json_pointer& at) const;
    double number(const nlohmann::json::json_pointer& at, double min, double max) const;
    long integer(const nlohmann::json::json_pointer& at, long min, long max) const;
    // Refuses members of the object at `at` not named in `known`.
    void only_members(const nlohmann::json::json_pointer& at,
                      std::initializer_list<std::string_view> known) const;

  private:
    const nlohmann::json& value(const nlohmann::json::json_pointer& at) const;
    std::string location(std::size_t offset) const;

    std::string file_;
    nlohmann::json root_;
    std::map<std::string, std::size_t> offsets_;  // by JSON pointer
    std::vector<std::size_t> line_starts_;
};

// Reads a whole file (at most 1 MiB) into a JsonDocument. Throws JsonError naming the file.
JsonDocument read_json_file(const std::string& path);

}  // namespace vibscore::feedback
