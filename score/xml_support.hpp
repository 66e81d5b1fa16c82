#pragma once

#include <pugixml.hpp>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "score/document_error.hpp"
#include "score/line_index.hpp"

namespace vibscore::xml {

// A parsed XML text that can say where each of its nodes came from, and the strict value readers
// both document kinds share. Malformed XML throws DocumentError naming the line and column.
class Source {
  public:
    Source(std::string_view text, std::string file);

    pugi::xml_node root() const { return document_.document_element(); }
    const std::string& file() const { return lines_.file(); }
    SourceLocation where(pugi::xml_node node) const;
    SourceLocation where_offset(std::ptrdiff_t offset) const;

  private:
    LineIndex lines_;
    pugi::xml_document document_;
};

// Reports attributes of node not named in allowed.
void check_attributes(const Source& source, pugi::xml_node node,
                      std::initializer_list<std::string_view> allowed, DiagnosticSink& sink);

// Reports non-blank text directly inside an element that holds only elements.
void check_no_text(const Source& source, pugi::xml_node node, DiagnosticSink& sink);

// A finite decimal number in [min, max], from an element's text or an attribute's value.
std::optional<double> read_number(const Source& source, pugi::xml_node at, std::string_view what,
                                  std::string_view text, double min, double max,
                                  DiagnosticSink& sink);

// A whole number in [min, max].
std::optional<std::int64_t> read_integer(const Source& source, pugi::xml_node at,
                                         std::string_view what, std::string_view text,
                                         std::int64_t min, std::int64_t max, DiagnosticSink& sink);

std::string_view trim(std::string_view text);

// Shortest text that reads back as exactly the same double.
std::string format_number(double value);

// The document serialised with two-space indentation and an XML declaration.
std::string to_text(const pugi::xml_document& document);

// The name of the root element, or "" when the text is not well-formed XML.
std::string root_name(std::string_view text);

}  // namespace vibscore::xml
