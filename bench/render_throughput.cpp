// Render throughput: a 10-minute score with every kind of tone, rendered at 8 kHz in the
// streaming chunks a player uses. Prints a table and one JSON line; asserts nothing.
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "daemon/render/performance.hpp"
#include "daemon/render/sampler.hpp"
#include "score/clef_xml.hpp"
#include "score/score_xml.hpp"

namespace {

using namespace vibscore;

constexpr double kRate = 8000.0;
constexpr std::size_t kChunk = 4096;
constexpr int kRepeats = 7;

double cpu_seconds() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9;
}

const char* const kSineClef = R"(<VibClef type="sine"><Tempo>0.5</Tempo><Numbers>
<Number>0.2</Number><Number>0.3</Number><Number>0.4</Number><Number>0.5</Number>
<Number>0.6</Number><Number>0.7</Number><Number>0.8</Number><Number>0.9</Number>
<Number>1</Number></Numbers><Strings><String>155</String><String>170</String>
<String>185</String><String>200</String><String>215</String><String>235</String>
</Strings></VibClef>)";

const char* const kCurveClef = R"(<VibClef type="curve"><Tempo>0.5</Tempo><Numbers>
<Number>0.2</Number><Number>0.4</Number><Number>0.6</Number><Number>0.8</Number>
<Number>1</Number></Numbers><Strings>
<String><Point time="0" level="0"/><Point time="0.3" level="1"/><Point time="0.7" level="0.4"/><Point time="1" level="0"/></String>
<String><Point time="0" level="1"/><Point time="0.5" level="0.2"/><Point time="1" level="1"/></String>
<String><Point time="0" level="0"/><Point time="0.1" level="1"/><Point time="0.2" level="0"/><Point time="0.6" level="0.8"/><Point time="1" level="0"/></String>
</Strings></VibClef>)";

// 300 bars of 4 beats at 0.5 s per beat: 600 s. Sine and curve bars alternate; each bar has
// legato, portamento, crescendo, decrescendo, plain notes and a rest.
std::string ten_minute_score() {
    std::string text =
        "<VibScore><Title>bench</Title><Clef id=\"s\" href=\"s\"/>"
        "<Clef id=\"k\" href=\"k\"/>";
    for (int bar = 0; bar < 300; ++bar) {
        const bool sine = bar % 2 == 0;
        const int strings = sine ? 6 : 3;
        const int numbers = sine ? 9 : 5;
        const auto note = [&](const char* length, int i, const std::string& extra) {
            return std::string("<Note length=\"") + length + "\" number=\"" +
                   std::to_string(1 + (bar + i) % numbers) + "\" string=\"" +
                   std::to_string(1 + (bar * 7 + i) % strings) + "\" " + extra + "/>";
        };
        const auto serial = std::to_string(bar + 1);
        text += std::string("<Bar clef=\"") + (sine ? "s" : "k") + "\">";
        text += note("8th", 0, "legato=\"" + serial + "\"") +
                note("8th", 1, "legato=\"" + serial + "\"");
        text += note("8th", 2, "portamento=\"" + serial + "\"") +
                note("8th", 3, "portamento=\"" + serial + "\"");
        text +=
            note("8th", 4, "dynamics=\"crescendo\"") + note("16th", 5, "dynamics=\"crescendo\"");
        text += "<Rest length=\"16th\"/>";
        text += note("8th", 6, "dynamics=\"decrescendo\"") + note("32th", 7, "") +
                note("32th", 8, "") + "<Rest length=\"16th\"/>";
        text += "</Bar>";
    }
    return text + "</VibScore>";
}

struct Figures {
    double parse_ms = 0, perform_ms = 0, render_cpu_s = 0, signal_s = 0;
    std::uint64_t samples = 0;
    double checksum = 0;
};

Figures run_once(const std::string& score_text) {
    Figures figures;
    double start = cpu_seconds();
    auto parsed = read_score(score_text, "bench");
    auto bundle = bind_clefs(std::move(parsed), "bench", [](const ClefDeclaration& d, const auto&) {
        return read_clef(d.id == "s" ? kSineClef : kCurveClef, d.href);
    });
    figures.parse_ms = (cpu_seconds() - start) * 1e3;

    start = cpu_seconds();
    const render::Performance performance(bundle);
    figures.perform_ms = (cpu_seconds() - start) * 1e3;
    figures.signal_s = performance.duration();

    std::vector<double> chunk(kChunk);
    const auto total = render::sample_index_at(performance.duration(), kRate);
    start = cpu_seconds();
    for (std::uint64_t first = 0; first < total; first += kChunk) {
        const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, total - first));
        render::render_signal(performance, kRate, first, std::span(chunk).first(n));
        figures.checksum += chunk[n / 2];  // keeps the work observable
    }
    figures.render_cpu_s = cpu_seconds() - start;
    figures.samples = total;
    return figures;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc > 1) {
        std::printf(
            "usage: %s\n"
            "Renders a generated 10-minute score at 8 kHz %d times on one core and prints\n"
            "the median throughput (seconds of signal per CPU second), per-sample cost and peak\n"
            "resident memory, then one JSON line.\n",
            argv[0], kRepeats);
        return argc == 2 && std::string(argv[1]) == "--help" ? 0 : 2;
    }
    const std::string score = ten_minute_score();
    std::vector<Figures> runs;
    for (int i = 0; i < kRepeats; ++i) {
        runs.push_back(run_once(score));
    }
    std::sort(runs.begin(), runs.end(),
              [](const Figures& a, const Figures& b) { return a.render_cpu_s < b.render_cpu_s; });
    const Figures& median = runs[runs.size() / 2];
    const double throughput = median.signal_s / median.render_cpu_s;
    const double ns_per_sample = median.render_cpu_s * 1e9 / static_cast<double>(median.samples);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const double peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;

    std::printf("render throughput (median of %d runs, one core)\n", kRepeats);
    std::printf("  score                 %.0f s of signal, %zu bytes of XML\n", median.signal_s,
                score.size());
    std::printf("  parse + bind          %.2f ms CPU\n", median.parse_ms);
    std::printf("  build performance     %.2f ms CPU\n", median.perform_ms);
    std::printf("  render at 8 kHz       %.2f ms CPU for %llu samples (%.2f ns/sample)\n",
                median.render_cpu_s * 1e3, static_cast<unsigned long long>(median.samples),
                ns_per_sample);
    std::printf("  throughput            %.0f x real time (target >= 10000)\n", throughput);
    std::printf("  peak resident memory  %.1f MiB\n", peak_mib);
    std::printf(
        "{\"benchmark\":\"render_throughput\",\"signal_seconds\":%.1f,\"rate_hz\":%.0f,"
        "\"render_cpu_seconds\":%.6f,\"realtime_factor\":%.0f,\"ns_per_sample\":%.3f,"
        "\"parse_ms\":%.3f,\"perform_ms\":%.3f,\"peak_rss_mib\":%.2f,\"checksum\":%.6g}\n",
        median.signal_s, kRate, median.render_cpu_s, throughput, ns_per_sample, median.parse_ms,
        median.perform_ms, peak_mib, median.checksum);
    return 0;
}
