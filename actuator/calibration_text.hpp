#pragma once

#include <string>
#include <vector>

// The CSV reading the calibration's plans and recordings share (internal to the actuator library).
namespace vibscore::actuator::calibration::text {

// One non-blank line of a CSV text: its 1-based number, its text and its comma-separated fields
// (trimmed). `first`: the text's first non-blank line, the only place a header may be.
struct CsvLine {
    int number = 0;
    std::string text;
    std::vector<std::string> fields;
    bool first = false;
};
std::vector<CsvLine> csv_lines(const std::string& text);

// Whether a field starts like a number (a header's names do not).
bool looks_numeric(const std::string& field);

// The whole field as a finite number; otherwise std::invalid_argument
// "<where>: <column> must be a number, not '<field>'".
double parse_number(const std::string& field, const std::string& where, const char* column);

}  // namespace vibscore::actuator::calibration::text
