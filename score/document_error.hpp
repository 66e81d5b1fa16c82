#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace vibscore {

// Where in which file something is wrong. line and column are 1-based; 0 means "whole file".
struct SourceLocation {
    std::string file;
    int line = 0;
    int column = 0;
};

struct Diagnostic {
    SourceLocation where;
    std::string message;
};

// "file:line:column: message", the form editors and compilers use.
std::string format(const Diagnostic& diagnostic);

// A document could not be read, or is not a valid score or clef. Carries every problem found.
class DocumentError : public std::runtime_error {
  public:
    explicit DocumentError(std::vector<Diagnostic> diagnostics);
    DocumentError(SourceLocation where, std::string message);

    const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

  private:
    std::vector<Diagnostic> diagnostics_;
};

// Gathers problems so one run reports all of them, up to limits::diagnostics.
class DiagnosticSink {
  public:
    void report(SourceLocation where, std::string message);
    bool empty() const { return diagnostics_.empty(); }
    // Throws DocumentError when anything was reported.
    void throw_if_any() const;

  private:
    std::vector<Diagnostic> diagnostics_;
    bool truncated_ = false;
};

}  // namespace vibscore
