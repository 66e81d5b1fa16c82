#include "client/signal_output.hpp"

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "daemon/render/sampler.hpp"

namespace vibscore::client {

namespace {

constexpr std::size_t kChunk = 8192;

template <typename Consume>
void for_each_chunk(const render::Performance& performance, std::uint32_t rate, std::uint64_t total,
                    Consume&& consume) {
    std::vector<double> chunk(kChunk);
    for (std::uint64_t first = 0; first < total; first += kChunk) {
        const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, total - first));
        render::render_signal(performance, rate, first, std::span(chunk).first(n));
        consume(first, std::span<const double>(chunk).first(n));
    }
}

void append_number(std::string& out, double value) {
    std::array<char, 32> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    out.append(buffer.data(), result.ptr);
}

template <typename T>
void put_le(std::ostream& out, T value) {
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        out.put(static_cast<char>((static_cast<std::uint64_t>(value) >> (8 * i)) & 0xff));
    }
}

constexpr std::string_view kCsvHeader = "t,y\n";

// The bytes of one CSV number as append_number writes it.
std::uint64_t number_chars(double value) {
    std::array<char, 32> buffer{};
    return static_cast<std::uint64_t>(
        std::to_chars(buffer.data(), buffer.data() + buffer.size(), value).ptr - buffer.data());
}

// "4294967296 bytes (4 GiB)".
std::string bytes_text(std::uint64_t bytes) {
    std::string text = std::to_string(bytes) + " bytes";
    if (bytes >= (std::uint64_t{1} << 30) && bytes % (std::uint64_t{1} << 30) == 0) {
        text += " (" + std::to_string(bytes >> 30) + " GiB)";
    }
    return text;
}

// The header (RIFF, fmt with cbSize, fact, data) and 4 bytes a sample.
std::uint64_t wav_size(std::uint64_t samples) {
    return 58 + samples * sizeof(float);
}

[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& size,
                         std::uint64_t max_bytes, std::uint32_t rate) {
    throw SignalTooLarge(
        path.string() + " would take " + size + ", more than the " + bytes_text(max_bytes) +
        " a signal file may take; use a lower --rate than " + std::to_string(rate) + " Hz");
}

void write_csv(std::ostream& out, const render::Performance& performance, std::uint32_t rate,
               std::uint64_t total) {
    out << kCsvHeader;
    std::string text;
    for_each_chunk(performance, rate, total, [&](std::uint64_t first, std::span<const double> y) {
        text.clear();
        for (std::size_t i = 0; i < y.size(); ++i) {
            append_number(text, static_cast<double>(first + i) / rate);
            text += ',';
            append_number(text, y[i]);
            text += '\n';
        }
        out << text;
    });
}

void write_wav(std::ostream& out, const render::Performance& performance, std::uint32_t rate,
               std::uint64_t total) {
    constexpr std::uint16_t kIeeeFloat = 3;
    constexpr std::uint32_t kFmtSize = 18;  // non-PCM formats carry cbSize
    const std::uint64_t data_bytes = total * sizeof(float);
    const std::uint64_t riff_bytes = 4 + (8 + kFmtSize) + (8 + 4) + (8 + data_bytes);
    if (riff_bytes > std::numeric_limits<std::uint32_t>::max()) {
        throw std::runtime_error("the signal is too long for a WAV file (4 GiB); use a lower rate");
    }
    out.write("RIFF", 4);
    put_le<std::uint32_t>(out, static_cast<std::uint32_t>(riff_bytes));
    out.write("WAVEfmt ", 8);
    put_le<std::uint32_t>(out, kFmtSize);
    put_le<std::uint16_t>(out, kIeeeFloat);
    put_le<std::uint16_t>(out, 1);  // mono
    put_le<std::uint32_t>(out, rate);
    put_le<std::uint32_t>(out, rate * sizeof(float));
    put_le<std::uint16_t>(out, sizeof(float));
    put_le<std::uint16_t>(out, 32);
    put_le<std::uint16_t>(out, 0);
    out.write("fact", 4);
    put_le<std::uint32_t>(out, 4);
    put_le<std::uint32_t>(out, static_cast<std::uint32_t>(total));
    out.write("data", 4);
    put_le<std::uint32_t>(out, static_cast<std::uint32_t>(data_bytes));
    std::vector<char> bytes;
    for_each_chunk(performance, rate, total, [&](std::uint64_t, std::span<const double> y) {
        bytes.resize(y.size() * sizeof(float));
        for (std::size_t i = 0; i < y.size(); ++i) {
            const auto sample = static_cast<float>(y[i]);
            std::uint32_t bits = 0;
            std::memcpy(&bits, &sample, sizeof bits);
            for (std::size_t b = 0; b < 4; ++b) {
                bytes[i * 4 + b] = static_cast<char>((bits >> (8 * b)) & 0xff);
            }
        }
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    });
}

}  // namespace

CsvSize csv_size_bounds(std::uint64_t samples) {
    // Far below 2^64 for any count of samples a score of at most an hour can have.
    return {kCsvHeader.size() + samples * 4,
            kCsvHeader.size() + samples * (2 * kMaxNumberChars + 2)};
}

std::uint64_t csv_size(const render::Performance& performance, std::uint32_t rate) {
    const auto total = render::sample_index_at(performance.duration(), rate);
    std::uint64_t bytes = kCsvHeader.size();
    for_each_chunk(performance, rate, total, [&](std::uint64_t first, std::span<const double> y) {
        for (std::size_t i = 0; i < y.size(); ++i) {
            bytes += number_chars(static_cast<double>(first + i) / rate) + number_chars(y[i]) + 2;
        }
    });
    return bytes;
}

SignalFormat signal_format_for(const std::filesystem::path& path) {
    const auto extension = path.extension().string();
    if (extension == ".csv") {
        return SignalFormat::csv;
    }
    if (extension == ".wav") {
        return SignalFormat::wav;
    }
    throw std::invalid_argument("cannot tell the format of \"" + path.string() +
                                "\": name it .csv or .wav");
}

std::uint64_t write_signal(const render::Performance& performance, std::uint32_t rate,
                           const std::filesystem::path& path, std::uint64_t max_bytes) {
    const auto format = signal_format_for(path);
    const auto total = render::sample_index_at(performance.duration(), rate);
    if (format == SignalFormat::csv) {
        // Refused before a byte is written: at once when even the shortest rows are too many,
        // after counting the rows when only the longest would be.
        const auto bounds = csv_size_bounds(total);
        if (bounds.least > max_bytes) {
            refuse(path, "at least " + bytes_text(bounds.least), max_bytes, rate);
        }
        if (bounds.most > max_bytes) {
            if (const auto bytes = csv_size(performance, rate); bytes > max_bytes) {
                refuse(path, bytes_text(bytes), max_bytes, rate);
            }
        }
    } else if (const auto bytes = wav_size(total); bytes > max_bytes) {
        refuse(path, bytes_text(bytes), max_bytes, rate);
    }
    auto temporary = path;
    temporary += ".partial";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) {
            throw std::runtime_error(temporary.string() +
                                     ": cannot create: " + std::strerror(errno));
        }
        try {
            format == SignalFormat::csv ? write_csv(out, performance, rate, total)
                                        : write_wav(out, performance, rate, total);
        } catch (...) {
            out.close();
            std::filesystem::remove(temporary);
            throw;
        }
        out.flush();
        if (!out) {
            const std::string reason = std::strerror(errno);
            out.close();
            std::filesystem::remove(temporary);
            throw std::runtime_error(path.string() + ": write failed: " + reason);
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary);
        throw std::runtime_error(path.string() + ": " + error.message());
    }
    return total;
}

}  // namespace vibscore::client
