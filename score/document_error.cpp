#include "score/document_error.hpp"

#include "score/limits.hpp"

namespace vibscore {

namespace {

std::string join(const std::vector<Diagnostic>& diagnostics) {
    std::string text;
    for (const auto& diagnostic : diagnostics) {
        if (!text.empty()) {
            text += '\n';
        }
        text += format(diagnostic);
    }
    return text;
}

}  // namespace

std::string format(const Diagnostic& diagnostic) {
    std::string text = diagnostic.where.file.empty() ? "<document>" : diagnostic.where.file;
    if (diagnostic.where.line > 0) {
        text += ':' + std::to_string(diagnostic.where.line) + ':' +
                std::to_string(diagnostic.where.column);
    }
    return text + ": " + diagnostic.message;
}

DocumentError::DocumentError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join(diagnostics)), diagnostics_(std::move(diagnostics)) {}

DocumentError::DocumentError(SourceLocation where, std::string message)
    : DocumentError(std::vector<Diagnostic>{{std::move(where), std::move(message)}}) {}

void DiagnosticSink::report(SourceLocation where, std::string message) {
    if (diagnostics_.size() < limits::diagnostics) {
        diagnostics_.push_back({std::move(where), std::move(message)});
    } else if (!truncated_) {
        truncated_ = true;
        diagnostics_.push_back({{where.file}, "too many errors; giving up on this document"});
    }
}

void DiagnosticSink::throw_if_any() const {
    if (!diagnostics_.empty()) {
        throw DocumentError(diagnostics_);
    }
}

}  // namespace vibscore
