#include "score/score_xml.hpp"

#include <set>

#include "score/limits.hpp"
#include "score/xml_support.hpp"

namespace vibscore {

namespace {

bool valid_clef_id(std::string_view id) {
    if (id.empty() || id.size() > limits::id_chars) {
        return false;
    }
    for (const char c : id) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                        (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
        if (!ok) {
            return false;
        }
    }
    return true;
}

class ScoreReader {
  public:
    ScoreReader(std::string_view text, const std::string& file) : source_(text, file) {}

    ParsedScore read() {
        const auto root = source_.root();
        parsed_.where.document = source_.where(root);
        if (std::string_view(root.name()) != "VibScore") {
            throw DocumentError(source_.where(root), std::string("root element is <") +
                                                         root.name() + ">, expected <VibScore>");
        }
        xml::check_attributes(source_, root, {"version"}, sink_);
        xml::check_no_text(source_, root, sink_);
        if (const auto version = root.attribute("version")) {
            parsed_.score.version = version.value();
        }
        bool seen_title = false;
        for (const auto child : root.children()) {
            if (child.type() != pugi::node_element) {
                continue;
            }
            const std::string_view name = child.name();
            if (name == "Title") {
                if (seen_title) {
                    sink_.report(source_.where(child), "more than one <Title>");
                }
                seen_title = true;
                read_title(child);
            } else if (name == "Clef") {
                read_clef_declaration(child);
            } else if (name == "Bar") {
                read_bar(child);
            } else {
                sink_.report(source_.where(child), "unknown element <" + std::string(name) +
                                                       "> in <VibScore> (expected Title, Clef "
                                                       "or Bar)");
            }
        }
        check_bar_clefs();
        sink_.throw_if_any();
        return std::move(parsed_);
    }

  private:
    void read_title(pugi::xml_node node) {
        xml::check_attributes(source_, node, {}, sink_);
        for (const auto child : node.children()) {
            if (child.type() == pugi::node_element) {
                sink_.report(source_.where(child),
                             "unexpected element <" + std::string(child.name()) + "> in <Title>");
            }
        }
        parsed_.score.title = std::string(xml::trim(node.child_value()));
        if (parsed_.score.title.size() > limits::title_chars) {
            sink_.report(source_.where(node),
                         "title is " + std::to_string(parsed_.score.title.size()) +
                             " bytes long; the limit is " + std::to_string(limits::title_chars));
        }
    }

    void read_clef_declaration(pugi::xml_node node) {
        xml::check_attributes(source_, node, {"id", "href"}, sink_);
        xml::check_no_text(source_, node, sink_);
        ClefDeclaration clef{node.attribute("id").value(), node.attribute("href").value()};
        if (!valid_clef_id(clef.id)) {
            sink_.report(source_.where(node),
                         "clef id \"" + clef.id + "\" must be 1 to " +
                             std::to_string(limits::id_chars) +
                             " characters of letters, digits, '-', '_' or '.'");
        } else if (!declared_.insert(clef.id).second) {
            sink_.report(source_.where(node), "clef id \"" + clef.id + "\" is declared twice");
        }
        if (clef.href.empty() || clef.href.size() > limits::href_chars) {
            sink_.report(source_.where(node), "clef \"" + clef.id + "\" needs an href of 1 to " +
                                                  std::to_string(limits::href_chars) +
                                                  " characters naming its VibClef document");
        }
        if (parsed_.score.clefs.size() == limits::clefs_per_score) {
            sink_.report(
                source_.where(node),
                "more than " + std::to_string(limits::clefs_per_score) + " clefs declared");
        }
        parsed_.score.clefs.push_back(std::move(clef));
        parsed_.where.clefs.push_back(source_.where(node));
    }

    void read_bar(pugi::xml_node node) {
        if (parsed_.score.bars.size() == limits::bars) {
            sink_.report(source_.where(node),
                         "more than " + std::to_string(limits::bars) + " bars");
            sink_.throw_if_any();
        }
        xml::check_attributes(source_, node, {"clef"}, sink_);
        xml::check_no_text(source_, node, sink_);
        Bar bar{node.attribute("clef").value(), {}};
        std::vector<SourceLocation> where;
        for (const auto child : node.children()) {
            if (child.type() != pugi::node_element) {
                continue;
            }
            if (++symbol_count_ > limits::symbols) {
                sink_.report(source_.where(child),
                             "more than " + std::to_string(limits::symbols) + " symbols");
                sink_.throw_if_any();
            }
            const std::string_view name = child.name();
            if (name == "Note") {
                bar.symbols.emplace_back(read_note(child));
            } else if (name == "Rest") {
                bar.symbols.emplace_back(read_rest(child));
            } else if (name == "Blank") {
                xml::check_attributes(source_, child, {}, sink_);
                xml::check_no_text(source_, child, sink_);
                bar.symbols.emplace_back(Blank{});
            } else {
                sink_.report(source_.where(child), "unknown element <" + std::string(name) +
                                                       "> in <Bar> (expected Note, Rest or Blank)");
                continue;
            }
            where.push_back(source_.where(child));
        }
        parsed_.where.bars.push_back(source_.where(node));
        parsed_.where.symbols.push_back(std::move(where));
        parsed_.score.bars.push_back(std::move(bar));
    }

    Length read_length(pugi::xml_node node) {
        const auto attribute = node.attribute("length");
        if (!attribute) {
            sink_.report(source_.where(node), std::string("<") + node.name() +
                                                  "> has no length (expected one of " +
                                                  std::string(length_spellings()) + ")");
            return Length::quarter;
        }
        const auto length = parse_length(attribute.value());
        if (!length) {
            sink_.report(source_.where(node), std::string("unknown length \"") + attribute.value() +
                                                  "\" (expected one of " +
                                                  std::string(length_spellings()) + ")");
            return Length::quarter;
        }
        return *length;
    }

    Note read_note(pugi::xml_node node) {
        xml::check_attributes(source_, node,
                              {"length", "number", "string", "dynamics", "legato", "portamento"},
                              sink_);
        xml::check_no_text(source_, node, sink_);
        Note note;
        note.length = read_length(node);
        note.number = static_cast<int>(
            required_integer(node, "number", 1, static_cast<int>(limits::numbers)));
        note.string = static_cast<int>(
            required_integer(node, "string", 1, static_cast<int>(limits::strings)));
        if (const auto dynamics = node.attribute("dynamics")) {
            const std::string_view value = dynamics.value();
            if (value == "crescendo") {
                note.dynamics = Dynamics::crescendo;
            } else if (value == "decrescendo") {
                note.dynamics = Dynamics::decrescendo;
            } else if (value != "none") {
                sink_.report(source_.where(node), "unknown dynamics \"" + std::string(value) +
                                                      "\" (expected crescendo, decrescendo or "
                                                      "none)");
            }
        }
        note.legato = optional_serial(node, "legato");
        note.portamento = optional_serial(node, "portamento");
        return note;
    }

    Rest read_rest(pugi::xml_node node) {
        xml::check_attributes(source_, node, {"length"}, sink_);
        xml::check_no_text(source_, node, sink_);
        return Rest{read_length(node)};
    }

    std::int64_t required_integer(pugi::xml_node node, const char* name, int min, int max) {
        const auto attribute = node.attribute(name);
        if (!attribute) {
            sink_.report(source_.where(node), std::string("<Note> has no ") + name + " (" +
                                                  std::to_string(min) + " to " +
                                                  std::to_string(max) + ")");
            return min;
        }
        return xml::read_integer(source_, node, name, attribute.value(), min, max, sink_)
            .value_or(min);
    }

    std::int64_t optional_serial(pugi::xml_node node, const char* name) {
        const auto attribute = node.attribute(name);
        if (!attribute) {
            return 0;
        }
        return xml::read_integer(source_, node, std::string(name) + " serial", attribute.value(), 0,
                                 limits::max_serial, sink_)
            .value_or(0);
    }

    void check_bar_clefs() {
        const auto& bars = parsed_.score.bars;
        for (size_t i = 0; i < bars.size(); ++i) {
            if (bars[i].clef.empty()) {
                sink_.report(parsed_.where.bars[i],
                             "<Bar> has no clef attribute (name one of the declared <Clef> ids)");
            } else if (!declared_.contains(bars[i].clef)) {
                sink_.report(parsed_.where.bars[i], "bar " + std::to_string(i + 1) +
                                                        " uses clef \"" + bars[i].clef +
                                                        "\", which no <Clef> declares");
            }
        }
    }

    xml::Source source_;
    DiagnosticSink sink_;
    ParsedScore parsed_;
    std::set<std::string, std::less<>> declared_;
    size_t symbol_count_ = 0;
};

void write_length(pugi::xml_node node, Length length) {
    node.append_attribute("length") = std::string(to_string(length)).c_str();
}

}  // namespace

ParsedScore read_score(std::string_view text, const std::string& file) {
    return ScoreReader(text, file).read();
}

std::string write_score(const Score& score) {
    pugi::xml_document document;
    auto root = document.append_child("VibScore");
    root.append_attribute("version") = score.version.c_str();
    if (!score.title.empty()) {
        root.append_child("Title").text() = score.title.c_str();
    }
    for (const auto& clef : score.clefs) {
        auto node = root.append_child("Clef");
        node.append_attribute("id") = clef.id.c_str();
        node.append_attribute("href") = clef.href.c_str();
    }
    for (const auto& bar : score.bars) {
        auto bar_node = root.append_child("Bar");
        bar_node.append_attribute("clef") = bar.clef.c_str();
        for (const auto& symbol : bar.symbols) {
            if (const auto* note = std::get_if<Note>(&symbol)) {
                auto node = bar_node.append_child("Note");
                write_length(node, note->length);
                node.append_attribute("number") = note->number;
                node.append_attribute("string") = note->string;
                if (note->dynamics != Dynamics::none) {
                    node.append_attribute("dynamics") =
                        std::string(to_string(note->dynamics)).c_str();
                }
                if (note->legato != 0) {
                    node.append_attribute("legato") = static_cast<long long>(note->legato);
                }
                if (note->portamento != 0) {
                    node.append_attribute("portamento") = static_cast<long long>(note->portamento);
                }
            } else if (const auto* rest = std::get_if<Rest>(&symbol)) {
                write_length(bar_node.append_child("Rest"), rest->length);
            } else {
                bar_node.append_child("Blank");
            }
        }
    }
    return xml::to_text(document);
}

}  // namespace vibscore
