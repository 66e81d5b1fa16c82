#include "daemon/registry/registry.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <system_error>
#include <type_traits>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/log.hpp"
#include "common/number_text.hpp"
#include "common/quoted_text.hpp"
#include "score/clef_xml.hpp"
#include "score/document_error.hpp"
#include "score/score_xml.hpp"
#include "score/xml_support.hpp"

namespace vibscore::daemon {

namespace {

using Code = RegistryError::Code;

constexpr std::string_view score_suffix = kScoreSuffix;
constexpr std::string_view clef_suffix = kClefSuffix;
constexpr std::string_view name_rule = kNameRule;

// The file label diagnostics carry: `score "alarm"`, so clients see names, not store paths.
std::string label(DocumentKind kind, std::string_view name) {
    return std::string(to_string(kind)) + " " + quoted_text(name);
}

void check_name(std::string_view name) {
    if (!is_valid_name(name)) {
        throw RegistryError(Code::invalid_document,
                            "invalid name " + quoted_text(name) + ": " + std::string(name_rule));
    }
}

std::string clef_title(const Clef& clef) {
    const auto strings = clef.strings.size();
    return std::string(to_string(clef.type)) + ", tempo " + rounded_text(clef.tempo) + " s, " +
           std::to_string(strings) + (strings == 1 ? " string" : " strings");
}

// One log line per diagnostic, so each gets the journald priority prefix.
void warn_skipped(const std::filesystem::path& path, const std::exception& error) {
    log::warning("registry: skipping " + path.string() + ":");
    std::string_view text = error.what();
    while (!text.empty()) {
        const auto end = std::min(text.find('\n'), text.size());
        log::warning("  " + std::string(text.substr(0, end)));
        text.remove_prefix(std::min(end + 1, text.size()));
    }
}

struct Listing {
    std::vector<std::pair<std::string, std::filesystem::path>> clefs, scores;
};

// The NAME.clef.xml and NAME.score.xml files of a directory, sorted by name. A missing shipped
// directory is only worth a warning; an unlistable store is an error the daemon must report.
Listing scan(const std::filesystem::path& directory, bool required) {
    Listing listing;
    std::error_code error;
    std::filesystem::directory_iterator entry(directory, error);
    for (; !error && entry != std::filesystem::directory_iterator(); entry.increment(error)) {
        const auto file_name = entry->path().filename().string();
        const bool is_clef = file_name.ends_with(clef_suffix);
        if ((!is_clef && !file_name.ends_with(score_suffix)) || is_temporary_file_name(file_name)) {
            continue;
        }
        const auto name = file_name.substr(
            0, file_name.size() - (is_clef ? clef_suffix.size() : score_suffix.size()));
        std::error_code type_error;
        if (!entry->is_regular_file(type_error)) {
            log::warning("registry: skipping " + entry->path().string() + ": not a regular file");
        } else if (!is_valid_name(name)) {
            log::warning("registry: skipping " + entry->path().string() + ": invalid name " +
                         quoted_text(name) + ": " + std::string(name_rule));
        } else {
            (is_clef ? listing.clefs : listing.scores).emplace_back(name, entry->path());
        }
    }
    if (error) {
        if (required) {
            throw std::system_error(error, directory.string() + ": cannot list");
        }
        log::warning("registry: no shipped documents: " + directory.string() + ": " +
                     error.message());
        return {};
    }
    std::sort(listing.clefs.begin(), listing.clefs.end());
    std::sort(listing.scores.begin(), listing.scores.end());
    return listing;
}

void ensure_directory(const std::filesystem::path& directory) {
    std::error_code error;
    if (std::filesystem::is_directory(directory, error)) {
        return;
    }
    const auto parent =
        directory.has_parent_path() ? directory.parent_path() : std::filesystem::path(".");
    std::filesystem::create_directories(parent, error);
    if (error) {
        throw std::system_error(error, parent.string() + ": cannot create");
    }
    if (::mkdir(directory.c_str(), 0755) != 0 && errno != EEXIST) {
        throw std::system_error(errno, std::generic_category(),
                                directory.string() + ": cannot create the store directory");
    }
    // The new directory entry must be durable before anything stored inside it is.
    sync_directory(parent);
    log::info("registry: created store directory " + directory.string());
}

template <typename Record>
const Record* find_in(const std::map<std::string, Record, std::less<>>& records,
                      std::string_view name) {
    const auto found = records.find(name);
    return found == records.end() ? nullptr : &found->second;
}

}  // namespace

// Only a bare name is accepted: hrefs come from clients, and resolving them as paths would let a
// document make the daemon read any file.
std::string clef_name_of(const ClefDeclaration& declaration, const SourceLocation& declared_at) {
    if (declaration.href.find('/') != std::string::npos) {
        throw DocumentError(declared_at, "clef " + quoted_text(declaration.id) + ": href " +
                                             quoted_text(declaration.href) +
                                             " is a path; the registry finds clefs by name only "
                                             "(NAME.clef.xml), unless Play sends the clef along");
    }
    auto name = clef_name_in_href(declaration.href);
    if (!name) {
        throw DocumentError(
            declared_at, "clef " + quoted_text(declaration.id) + ": href " +
                             quoted_text(declaration.href) +
                             " does not name a registry clef (NAME.clef.xml, NAME.xml or NAME; " +
                             std::string(name_rule) + ")");
    }
    return std::move(*name);
}

std::string_view to_string(RegistryError::Code code) {
    switch (code) {
        case Code::invalid_document:
            return "invalid-document";
        case Code::not_found:
            return "not-found";
        case Code::permission_denied:
            return "permission-denied";
        case Code::limit_exceeded:
            return "limit-exceeded";
        case Code::in_use:
            return "in-use";
    }
    return "unknown";
}

Registry::Registry(std::filesystem::path shipped_dir, std::filesystem::path store_dir,
                   StoreLimits store_limits)
    : shipped_dir_(std::move(shipped_dir)),
      store_dir_(std::move(store_dir)),
      limits_(store_limits) {
    ensure_directory(store_dir_);
    for (const auto& stale : remove_stale_temporaries(store_dir_)) {
        log::info("registry: removed " + stale.string() + ", left by an interrupted write");
    }
    const auto shipped = scan(shipped_dir_, false);
    const auto stored = scan(store_dir_, true);
    // Scores are checked against their clefs, so every clef must be in place first.
    for (const auto& [name, path] : shipped.clefs) {
        load_clef(path, name, true);
    }
    for (const auto& [name, path] : stored.clefs) {
        load_clef(path, name, false);
    }
    for (const auto& [name, path] : shipped.scores) {
        load_score(path, name, true);
    }
    for (const auto& [name, path] : stored.scores) {
        load_score(path, name, false);
    }
    log::info("registry: " + std::to_string(shipped_scores_.size()) + " scores and " +
              std::to_string(shipped_clefs_.size()) + " clefs shipped in " + shipped_dir_.string() +
              "; " + std::to_string(stored_scores_.size()) + " scores and " +
              std::to_string(stored_clefs_.size()) + " clefs stored in " + store_dir_.string());
}

// A file that fails to load is skipped, never fatal: one bad document must not take the daemon
// and every other document down with it.
void Registry::load_clef(const std::filesystem::path& path, const std::string& name, bool shipped) {
    try {
        auto text = read_document_file(path);
        ClefRecord record{{}, {}, read_clef(text, label(DocumentKind::clef, name))};
        record.title = clef_title(record.clef);
        record.text = std::move(text);
        if (!shipped) {
            stored_bytes_ += record.text.size();
        }
        (shipped ? shipped_clefs_ : stored_clefs_).insert_or_assign(name, std::move(record));
    } catch (const std::exception& error) {
        warn_skipped(path, error);
    }
}

void Registry::load_score(const std::filesystem::path& path, const std::string& name,
                          bool shipped) {
    try {
        auto text = read_document_file(path);
        const auto file = label(DocumentKind::score, name);
        auto record = bind(read_score(text, file), file);
        record.text = std::move(text);
        if (!shipped) {
            stored_bytes_ += record.text.size();
        }
        (shipped ? shipped_scores_ : stored_scores_).insert_or_assign(name, std::move(record));
    } catch (const std::exception& error) {
        warn_skipped(path, error);
    }
}

const Registry::ClefRecord* Registry::find_clef(std::string_view name) const {
    const auto* stored = find_in(stored_clefs_, name);
    return stored != nullptr ? stored : find_in(shipped_clefs_, name);
}

const Registry::ScoreRecord* Registry::find_score(std::string_view name) const {
    const auto* stored = find_in(stored_scores_, name);
    return stored != nullptr ? stored : find_in(shipped_scores_, name);
}

bool Registry::contains(DocumentKind kind, std::string_view name) const {
    return kind == DocumentKind::clef ? find_clef(name) != nullptr : find_score(name) != nullptr;
}

std::string_view to_string(Origin origin) {
    switch (origin) {
        case Origin::shipped:
            return "shipped";
        case Origin::stored:
            return "stored";
        case Origin::stored_over_shipped:
            return "stored-over-shipped";
    }
    return "stored";
}

Origin Registry::origin(DocumentKind kind, std::string_view name) const {
    check_name(name);
    const bool stored =
        kind == DocumentKind::clef ? stored_clefs_.contains(name) : stored_scores_.contains(name);
    const bool shipped =
        kind == DocumentKind::clef ? shipped_clefs_.contains(name) : shipped_scores_.contains(name);
    if (!stored && !shipped) {
        throw RegistryError(Code::not_found, "no " + label(kind, name));
    }
    return !stored ? Origin::shipped : shipped ? Origin::stored_over_shipped : Origin::stored;
}

std::vector<RegistryEntry> Registry::list(DocumentKind kind) const {
    std::map<std::string_view, RegistryEntry> visible;
    const auto add = [&](const auto& records, bool shipped) {
        for (const auto& [name, record] : records) {
            if constexpr (std::is_same_v<std::decay_t<decltype(record)>, ClefRecord>) {
                visible.insert_or_assign(name, RegistryEntry{name, record.title, shipped});
            } else {
                visible.insert_or_assign(name,
                                         RegistryEntry{name, record.bundle.score.title, shipped});
            }
        }
    };
    // Stored documents go in last so they replace the shipped ones they shadow.
    if (kind == DocumentKind::clef) {
        add(shipped_clefs_, true);
        add(stored_clefs_, false);
    } else {
        add(shipped_scores_, true);
        add(stored_scores_, false);
    }
    std::vector<RegistryEntry> entries;
    entries.reserve(visible.size());
    for (auto& [name, entry] : visible) {
        entries.push_back(std::move(entry));
    }
    return entries;
}

std::string Registry::get(DocumentKind kind, std::string_view name) const {
    check_name(name);
    const std::string* text = nullptr;
    if (kind == DocumentKind::clef) {
        const auto* record = find_clef(name);
        text = record != nullptr ? &record->text : nullptr;
    } else {
        const auto* record = find_score(name);
        text = record != nullptr ? &record->text : nullptr;
    }
    if (text == nullptr) {
        throw RegistryError(Code::not_found, "no " + label(kind, name));
    }
    return *text;
}

ScoreBundle Registry::score(std::string_view name) const {
    check_name(name);
    const auto* record = find_score(name);
    if (record == nullptr) {
        throw RegistryError(Code::not_found, "no " + label(DocumentKind::score, name));
    }
    return record->bundle;
}

Clef Registry::clef(std::string_view name) const {
    check_name(name);
    const auto* record = find_clef(name);
    if (record == nullptr) {
        throw RegistryError(Code::not_found, "no " + label(DocumentKind::clef, name));
    }
    return record->clef;
}

ScoreBundle Registry::inline_score(std::string_view document,
                                   const std::map<std::string, std::string>& clef_documents) const {
    std::size_t bytes = document.size();
    for (const auto& [href, text] : clef_documents) {
        bytes += text.size();
    }
    if (bytes > limits_.document_bytes) {
        throw RegistryError(Code::limit_exceeded,
                            "inline score and clefs are " + std::to_string(bytes) +
                                " bytes; the limit is " + std::to_string(limits_.document_bytes));
    }
    if (clef_documents.size() > limits::clefs_per_score) {
        throw RegistryError(Code::limit_exceeded, std::to_string(clef_documents.size()) +
                                                      " inline clefs; the limit is " +
                                                      std::to_string(limits::clefs_per_score));
    }
    const std::string file = "<inline score>";
    try {
        std::map<std::string, Clef> inline_clefs;
        for (const auto& [href, text] : clef_documents) {
            inline_clefs.emplace(href, read_clef(text, "<inline clef " + quoted_text(href) + ">"));
        }
        auto parsed = read_score(document, file);
        for (const auto& inline_clef : inline_clefs) {
            // Not a structured binding: clang 14 cannot capture one in the lambda below.
            const std::string& href = inline_clef.first;
            if (std::none_of(
                    parsed.score.clefs.begin(), parsed.score.clefs.end(),
                    [&](const ClefDeclaration& declared) { return declared.href == href; })) {
                throw RegistryError(Code::invalid_document,
                                    "inline clef " + quoted_text(href) +
                                        " is not named by any <Clef href> of the score");
            }
        }
        return bind(std::move(parsed), file, {}, nullptr, &inline_clefs).bundle;
    } catch (const DocumentError& error) {
        throw RegistryError(Code::invalid_document, error.what());
    }
}

Registry::ScoreRecord Registry::bind(ParsedScore parsed, std::string file,
                                     std::string_view replaced_name, const Clef* replacement,
                                     const std::map<std::string, Clef>* inline_clefs) const {
    ScoreRecord record;
    record.bundle = bind_clefs(
        std::move(parsed), std::move(file),
        [&](const ClefDeclaration& declaration, const SourceLocation& declared_at) -> Clef {
            if (inline_clefs != nullptr) {
                if (const auto sent = inline_clefs->find(declaration.href);
                    sent != inline_clefs->end()) {
                    return sent->second;
                }
            }
            auto name = clef_name_of(declaration, declared_at);
            const Clef* clef = nullptr;
            if (replacement != nullptr && name == replaced_name) {
                clef = replacement;
            } else if (const auto* found = find_clef(name)) {
                clef = &found->clef;
            }
            if (clef == nullptr) {
                throw DocumentError(declared_at, "clef " + quoted_text(declaration.id) +
                                                     ": no clef named " + quoted_text(name) +
                                                     " in the registry");
            }
            record.clef_names.push_back(std::move(name));
            return *clef;
        });
    std::sort(record.clef_names.begin(), record.clef_names.end());
    record.clef_names.erase(std::unique(record.clef_names.begin(), record.clef_names.end()),
                            record.clef_names.end());
    return record;
}

std::vector<Registry::Rebound> Registry::rebind_dependents(std::string_view name, const Clef& clef,
                                                           RegistryError::Code code,
                                                           std::string_view context) const {
    std::vector<Rebound> rebound;
    std::string problems;
    const auto visit = [&](const Records<ScoreRecord>& records, bool shipped) {
        for (const auto& [score_name, record] : records) {
            if (!std::binary_search(record.clef_names.begin(), record.clef_names.end(), name)) {
                continue;
            }
            try {
                auto bound = bind(ParsedScore{record.bundle.score, record.bundle.where},
                                  record.bundle.file, name, &clef);
                rebound.push_back({shipped, score_name, std::move(bound.bundle)});
            } catch (const DocumentError& error) {
                problems += "\n" + std::string(shipped ? "shipped " : "") +
                            label(DocumentKind::score, score_name) + ":\n" + error.what();
            }
        }
    };
    // Shadowed shipped scores count too: deleting the stored score would reveal them.
    visit(stored_scores_, false);
    visit(shipped_scores_, true);
    if (!problems.empty()) {
        throw RegistryError(code, std::string(context) + problems);
    }
    return rebound;
}

std::vector<std::string> Registry::users_of(std::string_view clef_name) const {
    std::vector<std::string> users;
    const auto visit = [&](const Records<ScoreRecord>& records, bool shipped) {
        for (const auto& [score_name, record] : records) {
            if (std::binary_search(record.clef_names.begin(), record.clef_names.end(), clef_name)) {
                users.push_back(std::string(shipped ? "shipped " : "") +
                                label(DocumentKind::score, score_name));
            }
        }
    };
    visit(stored_scores_, false);
    visit(shipped_scores_, true);
    return users;
}

void Registry::commit(std::vector<Rebound> rebound) {
    for (auto& score : rebound) {
        (score.shipped ? shipped_scores_ : stored_scores_).at(score.name).bundle =
            std::move(score.bundle);
    }
}

std::filesystem::path Registry::stored_path(DocumentKind kind, std::string_view name) const {
    return store_dir_ / (std::string(name) +
                         std::string(kind == DocumentKind::clef ? clef_suffix : score_suffix));
}

void Registry::check_store_limits(DocumentKind kind, const std::string& name,
                                  std::size_t new_size) const {
    std::optional<std::size_t> old_size;
    if (kind == DocumentKind::clef) {
        if (const auto* old = find_in(stored_clefs_, name)) {
            old_size = old->text.size();
        }
    } else if (const auto* old = find_in(stored_scores_, name)) {
        old_size = old->text.size();
    }
    const auto what = label(kind, name);
    if (!old_size && stored_documents() + 1 > limits_.documents) {
        throw RegistryError(Code::limit_exceeded,
                            "cannot store " + what + ": the store already holds " +
                                std::to_string(stored_documents()) + " documents, the limit is " +
                                std::to_string(limits_.documents));
    }
    const auto total = stored_bytes_ - old_size.value_or(0) + new_size;
    if (total > limits_.total_bytes) {
        throw RegistryError(Code::limit_exceeded,
                            "cannot store " + what + " (" + std::to_string(new_size) +
                                " bytes): the store would hold " + std::to_string(total) +
                                " bytes, the limit is " + std::to_string(limits_.total_bytes));
    }
}

DocumentKind Registry::compose(std::string_view name, std::string_view document) {
    // Single-threaded here: nothing changes the registry between the two steps.
    return *commit_compose(prepare_compose(name, document));
}

// Each compose validates and prepares everything first, then writes the disk, then updates
// memory, so a refused or failed compose leaves both exactly as they were.
Registry::PreparedCompose Registry::prepare_compose(std::string_view name,
                                                    std::string_view document) const {
    check_name(name);
    PreparedCompose prepared;
    prepared.name_ = std::string(name);
    prepared.generation_ = generation_;
    if (document.size() > limits_.document_bytes) {
        throw RegistryError(Code::limit_exceeded, "document " + quoted_text(name) + " is " +
                                                      std::to_string(document.size()) +
                                                      " bytes; the limit is " +
                                                      std::to_string(limits_.document_bytes));
    }
    try {
        prepared.kind_ = document_kind(document, "document " + quoted_text(name));
    } catch (const DocumentError& error) {
        throw RegistryError(Code::invalid_document, error.what());
    }
    const auto file = label(prepared.kind_, name);
    if (prepared.kind_ == DocumentKind::clef) {
        ClefRecord record;
        try {
            record.clef = read_clef(document, file);
        } catch (const DocumentError& error) {
            throw RegistryError(Code::invalid_document, error.what());
        }
        record.title = clef_title(record.clef);
        record.text = document;
        prepared.rebound_ = rebind_dependents(prepared.name_, record.clef, Code::invalid_document,
                                              file + " does not fit the scores that use it:");
        prepared.clef_ = std::move(record);
    } else {
        ScoreRecord record;
        try {
            record = bind(read_score(document, file), file);
        } catch (const DocumentError& error) {
            throw RegistryError(Code::invalid_document, error.what());
        }
        record.text = document;
        prepared.score_ = std::move(record);
    }
    check_store_limits(prepared.kind_, prepared.name_, document.size());
    return prepared;
}

std::optional<DocumentKind> Registry::commit_compose(PreparedCompose prepared) {
    if (prepared.generation_ != generation_) {
        return std::nullopt;
    }
    const auto kind = prepared.kind_;
    const auto& name = prepared.name_;
    const auto file = label(kind, name);
    const auto path = stored_path(kind, name);
    const std::string& text =
        kind == DocumentKind::clef ? prepared.clef_->text : prepared.score_->text;
    write_file_atomically(path, text);

    ++generation_;
    if (kind == DocumentKind::clef) {
        auto& stored = stored_clefs_[name];
        stored_bytes_ = stored_bytes_ - stored.text.size() + text.size();
        stored = std::move(*prepared.clef_);
        commit(std::move(prepared.rebound_));
    } else {
        auto& stored = stored_scores_[name];
        stored_bytes_ = stored_bytes_ - stored.text.size() + text.size();
        stored = std::move(*prepared.score_);
    }
    log::info("registry: stored " + file + " in " + path.string());
    return kind;
}

void Registry::remove(DocumentKind kind, std::string_view name) {
    check_name(name);
    const auto what = label(kind, name);
    const bool is_clef = kind == DocumentKind::clef;
    const bool stored = is_clef ? stored_clefs_.contains(name) : stored_scores_.contains(name);
    const bool shipped = is_clef ? shipped_clefs_.contains(name) : shipped_scores_.contains(name);
    if (!stored) {
        if (shipped) {
            throw RegistryError(Code::permission_denied,
                                "cannot delete " + what + ": shipped documents are read-only");
        }
        throw RegistryError(Code::not_found, "no " + what);
    }

    std::vector<Rebound> rebound;
    if (is_clef) {
        // With a shipped clef behind it, the scores fall back to that clef if they fit it.
        if (const auto* fallback = find_in(shipped_clefs_, name)) {
            rebound = rebind_dependents(name, fallback->clef, Code::in_use,
                                        "cannot delete " + what + ": the shipped " + what +
                                            " it shadows does not fit the scores that use it:");
        } else if (const auto users = users_of(name); !users.empty()) {
            std::string list;
            for (const auto& user : users) {
                list += (list.empty() ? "" : ", ") + user;
            }
            throw RegistryError(Code::in_use, "cannot delete " + what + ": used by " + list);
        }
    }

    const auto path = stored_path(kind, name);
    remove_file_durably(path);
    ++generation_;

    if (is_clef) {
        const auto found = stored_clefs_.find(name);
        stored_bytes_ -= found->second.text.size();
        stored_clefs_.erase(found);
    } else {
        const auto found = stored_scores_.find(name);
        stored_bytes_ -= found->second.text.size();
        stored_scores_.erase(found);
    }
    commit(std::move(rebound));
    log::info("registry: deleted " + what + " from " + path.string() +
              (shipped ? "; the shipped one is visible again" : ""));
}

}  // namespace vibscore::daemon
