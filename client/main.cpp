// vibscore: the command-line client. Offline verbs work on files without the daemon. The verbs
// are a table (verb_table.cpp); this only hands the command line to it.
#include "client/verb_command_line.hpp"

int main(int argc, char** argv) {
    return vibscore::client::run_command_line(argc, argv);
}
