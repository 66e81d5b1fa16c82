#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "score/bundle.hpp"
#include "score/clef.hpp"
#include "score/limits.hpp"
#include "score/registry_names.hpp"

namespace vibscore::daemon {

// A request the registry refuses. The bus layer maps code() to a named D-Bus error and sends
// what() as its message, which names the document and the value at fault.
class RegistryError : public std::runtime_error {
  public:
    enum class Code { invalid_document, not_found, permission_denied, limit_exceeded, in_use };

    RegistryError(Code code, const std::string& message)
        : std::runtime_error(message), code_(code) {}

    Code code() const { return code_; }

  private:
    Code code_;
};

// "invalid-document", "not-found", ...: a stable spelling for error names and logs.
std::string_view to_string(RegistryError::Code code);

// Where a visible registry document comes from. A stored document shadows a shipped one of
// its name: composing over a shipped name keeps the shipped file, composing over a stored one
// replaces it for good, which is why a client asks.
enum class Origin { shipped, stored, stored_over_shipped };

// "shipped", "stored", "stored-over-shipped": the spelling on the bus (Origin).
std::string_view to_string(Origin origin);

struct RegistryEntry {
    std::string name;
    std::string title;  // a score's <Title>; for a clef e.g. "sine, tempo 0.2 s, 6 strings"
    bool shipped = false;
    bool operator==(const RegistryEntry&) const = default;
};

// How much the writable store may hold, so a client cannot fill the disk.
struct StoreLimits {
    std::size_t document_bytes = limits::document_bytes;
    std::size_t documents = 1000;
    std::size_t total_bytes = std::size_t{64} << 20;
};

// The registry clef a score's <Clef href> names ("lra-phone" for "lra-phone.clef.xml"). Throws
// DocumentError at declared_at for a path or an invalid name.
std::string clef_name_of(const ClefDeclaration& declaration, const SourceLocation& declared_at);

// score/registry_names.hpp: the naming rule, shared with the offline tools.
using vibscore::is_valid_name;

// The scores and clefs the daemon can play: read-only shipped documents plus a writable store
// that survives restarts and crashes. Both directories hold NAME.score.xml and NAME.clef.xml.
// Scores refer to clefs by name only (href "NAME.clef.xml"), never by path, so nothing a client
// sends can make the daemon read another file. Everything is held in memory after loading;
// writes reach memory only after they are durable on disk.
//
// Invariant: every score held (stored or shipped, shadowed or not) binds to the clefs currently
// visible; changes that would break one are refused.
//
// Single-threaded: the daemon's event loop owns it.
class Registry {
  public:
    // Creates store_dir if missing, removes stale temporary files from it and loads both
    // directories. Documents that fail to load are logged and skipped. Throws std::system_error
    // when store_dir cannot be created or listed.
    Registry(std::filesystem::path shipped_dir, std::filesystem::path store_dir,
             StoreLimits store_limits = {});

    // The visible documents of a class (stored ones shadow shipped ones), sorted by name.
    std::vector<RegistryEntry> list(DocumentKind kind) const;

    // The document text exactly as composed or shipped. Throws not_found.
    std::string get(DocumentKind kind, std::string_view name) const;

    // Validates document, stores it durably under name (replacing a stored document of the same
    // name and class, shadowing a shipped one) and returns its class, told by the root element.
    // Throws invalid_document, limit_exceeded; std::system_error when the disk write fails.
    // The same as commit_compose(prepare_compose(name, document)).
    DocumentKind compose(std::string_view name, std::string_view document);

    // A compose in two steps, so that the document's parsing and validation (all of the work)
    // can run where the registry is only read (the daemon's workers, under a reader's lock) and
    // only the store itself where it is written (issue 33, item 1).
    class PreparedCompose;
    // Everything compose() checks, against the registry as it is now; nothing is written.
    // Throws as compose() does, but never std::system_error.
    PreparedCompose prepare_compose(std::string_view name, std::string_view document) const;
    // Stores what prepare_compose() validated and returns its class, if the registry has not
    // changed since (no compose or delete stored in between: what it was checked against still
    // holds); std::nullopt, with nothing written, if it has. Throws std::system_error when the
    // disk write fails.
    [[nodiscard]] std::optional<DocumentKind> commit_compose(PreparedCompose prepared);
    // Counts the changes stored (composes and deletes).
    std::uint64_t generation() const { return generation_; }

    // Deletes a stored document; a shipped one of the same name becomes visible again.
    // Throws not_found, permission_denied (shipped only) or in_use (a clef a score needs).
    void remove(DocumentKind kind, std::string_view name);

    // A registry score with its clefs resolved from the registry. Throws not_found.
    ScoreBundle score(std::string_view name) const;

    // A VibScore document sent over the bus; nothing is stored. Its clefs are the VibClef
    // documents sent along with it, keyed by the href that names them (any href: it is a key, not
    // a path), and the registry's for the others. Throws invalid_document (also for a clef
    // document no <Clef> names) or limit_exceeded.
    ScoreBundle inline_score(std::string_view document,
                             const std::map<std::string, std::string>& clef_documents = {}) const;

    // A registry clef. Throws not_found.
    Clef clef(std::string_view name) const;

    bool contains(DocumentKind kind, std::string_view name) const;
    // Throws not_found.
    Origin origin(DocumentKind kind, std::string_view name) const;

    std::size_t stored_documents() const { return stored_clefs_.size() + stored_scores_.size(); }
    std::size_t stored_bytes() const { return stored_bytes_; }
    const std::filesystem::path& store_dir() const { return store_dir_; }
    const std::filesystem::path& shipped_dir() const { return shipped_dir_; }

  private:
    struct ClefRecord {
        std::string text;
        std::string title;
        Clef clef;
    };
    struct ScoreRecord {
        std::string text;
        ScoreBundle bundle;
        std::vector<std::string> clef_names;  // registry clefs it uses, by name
    };
    template <typename Record>
    using Records = std::map<std::string, Record, std::less<>>;

    // A held score bound again after a clef it uses changed.
    struct Rebound {
        bool shipped;
        std::string name;
        ScoreBundle bundle;
    };

    void load_clef(const std::filesystem::path& path, const std::string& name, bool shipped);
    void load_score(const std::filesystem::path& path, const std::string& name, bool shipped);

    const ClefRecord* find_clef(std::string_view name) const;
    const ScoreRecord* find_score(std::string_view name) const;

    // Binds a parsed score to registry clefs, with an optional replacement for one clef name.
    ScoreRecord bind(ParsedScore parsed, std::string file, std::string_view replaced_name = {},
                     const Clef* replacement = nullptr,
                     const std::map<std::string, Clef>* inline_clefs = nullptr) const;
    // Every held score that uses clef name, bound again with it replaced by clef. Throws a
    // RegistryError with code naming each score that no longer fits, after context.
    std::vector<Rebound> rebind_dependents(std::string_view name, const Clef& clef,
                                           RegistryError::Code code,
                                           std::string_view context) const;
    // "score \"a\"", "shipped score \"b\"": each held score that uses clef name.
    std::vector<std::string> users_of(std::string_view clef_name) const;
    void commit(std::vector<Rebound> rebound);

    void check_store_limits(DocumentKind kind, const std::string& name, std::size_t new_size) const;
    std::filesystem::path stored_path(DocumentKind kind, std::string_view name) const;

    std::filesystem::path shipped_dir_;
    std::filesystem::path store_dir_;
    StoreLimits limits_;
    Records<ClefRecord> shipped_clefs_, stored_clefs_;
    Records<ScoreRecord> shipped_scores_, stored_scores_;
    std::size_t stored_bytes_ = 0;
    std::uint64_t generation_ = 0;
};

// What Registry::prepare_compose() validated, for Registry::commit_compose().
class Registry::PreparedCompose {
  public:
    DocumentKind kind() const { return kind_; }
    const std::string& name() const { return name_; }

  private:
    friend class Registry;
    DocumentKind kind_ = DocumentKind::score;
    std::string name_;
    std::uint64_t generation_ = 0;  // of the registry it was checked against
    std::optional<ClefRecord> clef_;
    std::optional<ScoreRecord> score_;
    std::vector<Rebound> rebound_;  // the scores that use a composed clef, bound to it
};

}  // namespace vibscore::daemon
