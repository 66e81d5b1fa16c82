#include "common/log.hpp"

#include <sys/stat.h>
#include <sys/uio.h>
#include <systemd/sd-journal.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace vibscore::log {

namespace {

bool g_verbose = false;

bool valid_field_name(std::string_view name) {
    // journald: upper case, digits and '_', not starting with '_' (those are its own) or a digit.
    if (name.empty() || name.size() > 64 || name.front() == '_' ||
        (name.front() >= '0' && name.front() <= '9')) {
        return false;
    }
    for (const char c : name) {
        if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) {
            return false;
        }
    }
    return true;
}

Sink detect_sink() {
    struct stat status {};
    if (::fstat(STDERR_FILENO, &status) == 0 &&
        detail::names_stream(std::getenv("JOURNAL_STREAM"), status.st_dev, status.st_ino)) {
        return Sink::journal;
    }
    return ::isatty(STDERR_FILENO) == 1 ? Sink::terminal : Sink::stream;
}

Sink sink() {
    static const Sink decided = detect_sink();
    return decided;
}

void write_line(int priority, std::string_view message, Fields fields) {
    if (sink() == Sink::journal) {
        const auto entries = detail::journal_fields(priority, message, fields);
        std::vector<iovec> vector;
        vector.reserve(entries.size());
        for (const auto& entry : entries) {
            vector.push_back({const_cast<char*>(entry.data()), entry.size()});
        }
        if (sd_journal_sendv(vector.data(), static_cast<int>(vector.size())) >= 0) {
            return;
        }
        // The journal refused it (gone, full): the line still goes to stderr, which it reads.
    }
    const std::string line = detail::stream_line(sink() == Sink::journal ? Sink::stream : sink(),
                                                 priority, message, fields);
    // One write per line keeps lines whole when several processes share the terminal.
    [[maybe_unused]] const auto written = ::write(STDERR_FILENO, line.data(), line.size());
}

}  // namespace

namespace detail {

bool names_stream(const char* journal_stream, unsigned long long device, unsigned long long inode) {
    if (journal_stream == nullptr) {
        return false;
    }
    char* end = nullptr;
    const unsigned long long named_device = std::strtoull(journal_stream, &end, 10);
    if (end == journal_stream || *end != ':') {
        return false;
    }
    const char* inode_text = end + 1;
    const unsigned long long named_inode = std::strtoull(inode_text, &end, 10);
    return end != inode_text && *end == '\0' && named_device == device && named_inode == inode;
}

std::vector<std::string> journal_fields(int priority, std::string_view message, Fields fields) {
    std::vector<std::string> entries;
    entries.push_back("MESSAGE=" + std::string(message));
    entries.push_back("PRIORITY=" + std::to_string(priority));
    for (const auto& field : fields) {
        if (valid_field_name(field.name)) {
            entries.push_back(std::string(field.name) + "=" + field.value);
        }
    }
    return entries;
}

std::string stream_line(Sink sink, int priority, std::string_view message, Fields fields) {
    std::string line;
    if (sink == Sink::terminal) {
        line = priority <= 3 ? "error: " : priority == 4 ? "warning: " : "";
    } else {
        line = "<" + std::to_string(priority) + ">";
    }
    line.append(message);
    bool first = true;
    for (const auto& field : fields) {
        if (!valid_field_name(field.name)) {
            continue;
        }
        line += first ? " (" : ", ";
        line += std::string(field.name) + "=" + field.value;
        first = false;
    }
    if (!first) {
        line += ')';
    }
    line += '\n';
    return line;
}

}  // namespace detail

void error(std::string_view message, Fields fields) {
    write_line(3, message, fields);
}
void warning(std::string_view message, Fields fields) {
    write_line(4, message, fields);
}
void info(std::string_view message, Fields fields) {
    write_line(6, message, fields);
}
void debug(std::string_view message, Fields fields) {
    if (g_verbose) {
        write_line(7, message, fields);
    }
}
void set_verbose(bool verbose) {
    g_verbose = verbose;
}

}  // namespace vibscore::log
