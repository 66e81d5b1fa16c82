#pragma once

#include <ostream>
#include <string>

#include "actuator/declaration.hpp"
#include "client/clef_search.hpp"
#include "daemon/render/fitting/clef_fit.hpp"

namespace vibscore::client {

// A clef by file or registry name: a path when a file is there, else NAME (or NAME.clef.xml)
// looked up as a score's href is (--clefs folders, vibscored's registry, the shipped clefs).
// Throws DocumentError naming the file and line, or where it looked.
struct FoundClef {
    Clef clef;
    std::string origin;  // the file, or "registry"
};
FoundClef find_clef(const std::string& argument, const ClefSearch& clefs);

// The fitted clef as a document: a comment saying what it was fitted from and to, and why each
// change was made, then the VibClef.
std::string fitted_document(const render::ClefFit& fit, const std::string& written,
                            const actuator::Declaration& declaration);

struct ClefFitRequest {
    std::string clef;    // file or registry name
    std::string output;  // -o FILE; empty: standard output
    actuator::Declaration actuator;
};

// vibscore clef fit CLEF [--actuator FILE|daemon] [-o OUT]: writes the device clef and says on
// `err` what changed (or that the clef fits as written). exit_failed for a clef that cannot be
// read or fitted, or an output that cannot be written.
int fit_clef_document(const ClefFitRequest& request, const ClefSearch& clefs, std::ostream& out,
                      std::ostream& err);

}  // namespace vibscore::client
