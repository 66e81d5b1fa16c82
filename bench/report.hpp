#pragma once

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace vibscore::bench {

// Text made safe inside a JSON string: quotes and backslashes escaped, control characters
// dropped (the benchmarks' strings are names, paths and CPU models).
inline std::string json_escape(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        if (static_cast<unsigned char>(c) >= 0x20) {
            out += c;
        }
    }
    return out;
}

// A number for a JSON line: four significant digits, null for NaN or infinity (JSON has
// neither).
inline std::string json_number(double value) {
    if (!std::isfinite(value)) {
        return "null";
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

// The CPU the figures were measured on, as /proc/cpuinfo names it.
inline std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            const auto start = line.find_first_not_of(" \t", colon + 1);
            return start == std::string::npos ? "unknown" : line.substr(start);
        }
    }
    return "unknown";
}

}  // namespace vibscore::bench
