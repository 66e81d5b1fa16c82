#include "score/xml_support.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace vibscore::xml {

namespace {

constexpr unsigned kParseOptions = pugi::parse_default;

std::string quoted(std::string_view text) {
    constexpr size_t kShown = 40;
    std::string shown(text.substr(0, kShown));
    if (text.size() > kShown) {
        shown += "...";
    }
    return '"' + shown + '"';
}

}  // namespace

Source::Source(std::string_view text, std::string file) : lines_(text, std::move(file)) {
    const auto result =
        document_.load_buffer(text.data(), text.size(), kParseOptions, pugi::encoding_utf8);
    if (!result) {
        throw DocumentError(where_offset(result.offset),
                            std::string("malformed XML: ") + result.description());
    }
    if (!document_.document_element()) {
        throw DocumentError(where_offset(0), "malformed XML: no root element");
    }
}

SourceLocation Source::where_offset(std::ptrdiff_t offset) const {
    return lines_.at(offset);
}

SourceLocation Source::where(pugi::xml_node node) const {
    std::ptrdiff_t offset = node.offset_debug();
    // pugixml points at the element's name; people count from its '<'.
    if (offset > 0 && node.type() == pugi::node_element) {
        --offset;
    }
    return where_offset(offset);
}

void check_attributes(const Source& source, pugi::xml_node node,
                      std::initializer_list<std::string_view> allowed, DiagnosticSink& sink) {
    for (const auto attribute : node.attributes()) {
        const std::string_view name = attribute.name();
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
            std::string expected;
            for (const auto each : allowed) {
                expected += (expected.empty() ? "" : ", ") + std::string(each);
            }
            sink.report(source.where(node),
                        "unknown attribute " + std::string(name) + " on <" + node.name() + ">" +
                            (expected.empty() ? " (it takes none)"
                                              : " (expected one of " + expected + ")"));
        }
    }
}

void check_no_text(const Source& source, pugi::xml_node node, DiagnosticSink& sink) {
    for (const auto child : node.children()) {
        if ((child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) &&
            !trim(child.value()).empty()) {
            sink.report(source.where(child), "unexpected text " + quoted(trim(child.value())) +
                                                 " inside <" + node.name() + ">");
        }
    }
}

std::string_view trim(std::string_view text) {
    const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
    while (!text.empty() && blank(text.front())) {
        text.remove_prefix(1);
    }
    while (!text.empty() && blank(text.back())) {
        text.remove_suffix(1);
    }
    return text;
}

std::optional<double> read_number(const Source& source, pugi::xml_node at, std::string_view what,
                                  std::string_view text, double min, double max,
                                  DiagnosticSink& sink) {
    const auto value_text = trim(text);
    double value = 0.0;
    const auto* begin = value_text.data();
    const auto* end = begin + value_text.size();
    if (!value_text.empty() && value_text.front() == '+') {
        ++begin;
    }
    const auto [stop, error] = std::from_chars(begin, end, value);
    if (value_text.empty() || error != std::errc() || stop != end || !std::isfinite(value)) {
        sink.report(source.where(at), std::string(what) + " " + quoted(value_text) +
                                          " is not a finite decimal number");
        return std::nullopt;
    }
    if (value < min || value > max) {
        std::ostringstream range;
        range << what << " " << quoted(value_text) << " is out of range (" << min << " to " << max
              << ")";
        sink.report(source.where(at), range.str());
        return std::nullopt;
    }
    return value;
}

std::optional<std::int64_t> read_integer(const Source& source, pugi::xml_node at,
                                         std::string_view what, std::string_view text,
                                         std::int64_t min, std::int64_t max, DiagnosticSink& sink) {
    const auto value_text = trim(text);
    std::int64_t value = 0;
    const auto* end = value_text.data() + value_text.size();
    const auto [stop, error] = std::from_chars(value_text.data(), end, value);
    if (value_text.empty() || error != std::errc() || stop != end) {
        sink.report(source.where(at),
                    std::string(what) + " " + quoted(value_text) + " is not a whole number");
        return std::nullopt;
    }
    if (value < min || value > max) {
        sink.report(source.where(at), std::string(what) + " " + quoted(value_text) +
                                          " is out of range (" + std::to_string(min) + " to " +
                                          std::to_string(max) + ")");
        return std::nullopt;
    }
    return value;
}

std::string format_number(double value) {
    char buffer[64];
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
    return error == std::errc() ? std::string(buffer, end) : std::string("0");
}

std::string to_text(const pugi::xml_document& document) {
    std::ostringstream out;
    document.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
    return out.str();
}

std::string root_name(std::string_view text) {
    pugi::xml_document document;
    if (!document.load_buffer(text.data(), text.size(), kParseOptions, pugi::encoding_utf8)) {
        return {};
    }
    return document.document_element().name();
}

}  // namespace vibscore::xml
