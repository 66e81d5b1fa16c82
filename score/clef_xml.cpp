#include "score/clef_xml.hpp"

#include "score/document_error.hpp"
#include "score/limits.hpp"
#include "score/xml_support.hpp"

namespace vibscore {

namespace {

class ClefReader {
  public:
    ClefReader(std::string_view text, const std::string& file) : source_(text, file) {}

    Clef read() {
        const auto root = source_.root();
        if (std::string_view(root.name()) != "VibClef") {
            throw DocumentError(source_.where(root), std::string("root element is <") +
                                                         root.name() + ">, expected <VibClef>");
        }
        xml::check_attributes(source_, root, {"type", "version"}, sink_);
        xml::check_no_text(source_, root, sink_);
        read_type(root);
        if (const auto version = root.attribute("version")) {
            clef_.version = version.value();
        }
        bool seen_tempo = false;
        bool seen_strings = false;
        for (const auto child : root.children()) {
            if (child.type() != pugi::node_element) {
                continue;
            }
            const std::string_view name = child.name();
            if (name == "Tempo") {
                if (seen_tempo) {
                    sink_.report(source_.where(child), "more than one <Tempo>");
                }
                seen_tempo = true;
                read_tempo(child);
            } else if (name == "Numbers") {
                xml::check_attributes(source_, child, {}, sink_);
                xml::check_no_text(source_, child, sink_);
                for (const auto number : child.children()) {
                    if (number.type() != pugi::node_element) {
                        continue;
                    }
                    if (std::string_view(number.name()) == "Number") {
                        read_number(number);
                    } else {
                        unknown(number, "Numbers", "Number");
                    }
                }
            } else if (name == "Number") {
                read_number(child);
            } else if (name == "Strings") {
                if (seen_strings) {
                    sink_.report(source_.where(child), "more than one <Strings>");
                }
                seen_strings = true;
                read_strings(child);
            } else {
                unknown(child, "VibClef", "Tempo, Numbers or Strings");
            }
        }
        if (!seen_tempo) {
            sink_.report(source_.where(root),
                         "<VibClef> has no <Tempo> (seconds per quarter note)");
        }
        if (clef_.numbers.empty()) {
            sink_.report(source_.where(root),
                         "<VibClef> defines no <Number> (the amplitude of each note-head number)");
        }
        if (clef_.strings.empty()) {
            sink_.report(source_.where(root), "<VibClef> defines no <String> inside <Strings>");
        }
        sink_.throw_if_any();
        return std::move(clef_);
    }

  private:
    void unknown(pugi::xml_node node, std::string_view parent, std::string_view expected) {
        sink_.report(source_.where(node), "unknown element <" + std::string(node.name()) +
                                              "> in <" + std::string(parent) + "> (expected " +
                                              std::string(expected) + ")");
    }

    void read_type(pugi::xml_node root) {
        const auto type = root.attribute("type");
        const std::string_view value = type.value();
        if (value == "sine") {
            clef_.type = ClefType::sine;
        } else if (value == "curve") {
            clef_.type = ClefType::curve;
        } else if (value == "line") {
            clef_.type = ClefType::line;
        } else {
            sink_.report(source_.where(root),
                         type ? "unknown clef type \"" + std::string(value) +
                                    "\" (expected sine, curve or line)"
                              : std::string("<VibClef> has no type (sine, curve or line)"));
        }
    }

    void read_tempo(pugi::xml_node node) {
        xml::check_attributes(source_, node, {}, sink_);
        clef_.tempo = xml::read_number(source_, node, "tempo", node.child_value(),
                                       limits::min_tempo_s, limits::max_tempo_s, sink_)
                          .value_or(1.0);
    }

    void read_number(pugi::xml_node node) {
        xml::check_attributes(source_, node, {}, sink_);
        if (clef_.numbers.size() == limits::numbers) {
            sink_.report(source_.where(node), "more than " + std::to_string(limits::numbers) +
                                                  " <Number> elements (note heads carry 1 to " +
                                                  std::to_string(limits::numbers) + ")");
            return;
        }
        const auto what = "amplitude of number " + std::to_string(clef_.numbers.size() + 1);
        clef_.numbers.push_back(xml::read_number(source_, node, what, node.child_value(), 0.0,
                                                 limits::max_amplitude, sink_)
                                    .value_or(0.0));
    }

    void read_strings(pugi::xml_node node) {
        xml::check_attributes(source_, node, {}, sink_);
        xml::check_no_text(source_, node, sink_);
        for (const auto child : node.children()) {
            if (child.type() != pugi::node_element) {
                continue;
            }
            if (std::string_view(child.name()) != "String") {
                unknown(child, "Strings", "String");
                continue;
            }
            if (clef_.strings.size() == limits::strings) {
                sink_.report(source_.where(child), "more than " + std::to_string(limits::strings) +
                                                       " <String> elements (the staff has " +
                                                       std::to_string(limits::strings) + " lines)");
                return;
            }
            clef_.strings.push_back(clef_.type == ClefType::sine ? read_frequency(child)
                                                                 : read_points(child));
        }
    }

    ClefString read_frequency(pugi::xml_node node) {
        xml::check_attributes(source_, node, {}, sink_);
        for (const auto child : node.children()) {
            if (child.type() == pugi::node_element) {
                sink_.report(source_.where(child),
                             "<" + std::string(child.name()) +
                                 "> in a String of a sine clef (a sine String holds a frequency "
                                 "in Hz; Points belong to curve and line clefs)");
            }
        }
        const auto what = "frequency of string " + std::to_string(clef_.strings.size() + 1);
        ClefString string;
        const auto frequency = xml::read_number(source_, node, what, node.child_value(), 0.0,
                                                limits::max_frequency_hz, sink_);
        if (frequency && *frequency <= 0.0) {
            sink_.report(source_.where(node), what + " must be above 0 Hz");
        }
        string.frequency = frequency.value_or(1.0);
        return string;
    }

    ClefString read_points(pugi::xml_node node) {
        xml::check_attributes(source_, node, {}, sink_);
        xml::check_no_text(source_, node, sink_);
        const auto string_number = std::to_string(clef_.strings.size() + 1);
        ClefString string;
        for (const auto child : node.children()) {
            if (child.type() != pugi::node_element) {
                continue;
            }
            if (std::string_view(child.name()) != "Point") {
                unknown(child, "String", "Point");
                continue;
            }
            if (string.points.size() == limits::points_per_string) {
                sink_.report(source_.where(child), "string " + string_number + " has more than " +
                                                       std::to_string(limits::points_per_string) +
                                                       " points");
                break;
            }
            xml::check_attributes(source_, child, {"time", "level"}, sink_);
            ClefPoint point;
            for (const char* name : {"time", "level"}) {
                const auto attribute = child.attribute(name);
                if (!attribute) {
                    sink_.report(source_.where(child),
                                 std::string("<Point> has no ") + name + " (0 to 1)");
                    continue;
                }
                const auto value = xml::read_number(source_, child, std::string("point ") + name,
                                                    attribute.value(), 0.0, 1.0, sink_);
                (name[0] == 't' ? point.time : point.level) = value.value_or(0.0);
            }
            if (!string.points.empty() && point.time < string.points.back().time) {
                sink_.report(source_.where(child),
                             "point time " + xml::format_number(point.time) +
                                 " comes before the previous point's " +
                                 xml::format_number(string.points.back().time) +
                                 " (points must be in time order)");
            }
            string.points.push_back(point);
        }
        if (string.points.empty()) {
            sink_.report(source_.where(node), "string " + string_number + " of a " +
                                                  std::string(to_string(clef_.type)) +
                                                  " clef has no <Point>");
        }
        return string;
    }

    xml::Source source_;
    DiagnosticSink sink_;
    Clef clef_;
};

}  // namespace

Clef read_clef(std::string_view text, const std::string& file) {
    return ClefReader(text, file).read();
}

std::string write_clef(const Clef& clef) {
    pugi::xml_document document;
    auto root = document.append_child("VibClef");
    root.append_attribute("type") = std::string(to_string(clef.type)).c_str();
    root.append_attribute("version") = clef.version.c_str();
    root.append_child("Tempo").text() = xml::format_number(clef.tempo).c_str();
    auto numbers = root.append_child("Numbers");
    for (const double number : clef.numbers) {
        numbers.append_child("Number").text() = xml::format_number(number).c_str();
    }
    auto strings = root.append_child("Strings");
    for (const auto& string : clef.strings) {
        auto node = strings.append_child("String");
        if (clef.type == ClefType::sine) {
            node.text() = xml::format_number(string.frequency).c_str();
            continue;
        }
        for (const auto& point : string.points) {
            auto point_node = node.append_child("Point");
            point_node.append_attribute("time") = xml::format_number(point.time).c_str();
            point_node.append_attribute("level") = xml::format_number(point.level).c_str();
        }
    }
    return xml::to_text(document);
}

}  // namespace vibscore
