#pragma once

#include "client/verb_table.hpp"

// Each verb's arguments and options and what runs it (Verb::declare); the table in
// verb_table.cpp names them. On documents (verb_files.cpp):
namespace vibscore::client {

VerbHandler declare_check(CLI::App& command, VerbContext& context);
VerbHandler declare_render(CLI::App& command, VerbContext& context);
VerbHandler declare_convert(CLI::App& command, VerbContext& context);
VerbHandler declare_clef_fit(CLI::App& command, VerbContext& context);
VerbHandler declare_info(CLI::App& command, VerbContext& context);
VerbHandler declare_show(CLI::App& command, VerbContext& context);
VerbHandler declare_edit(CLI::App& command, VerbContext& context);

// On vibscored, its registry and the device (verb_device.cpp):
VerbHandler declare_play(CLI::App& command, VerbContext& context);
VerbHandler declare_stop(CLI::App& command, VerbContext& context);
VerbHandler declare_list(CLI::App& command, VerbContext& context);
VerbHandler declare_get(CLI::App& command, VerbContext& context);
VerbHandler declare_compose(CLI::App& command, VerbContext& context);
VerbHandler declare_delete(CLI::App& command, VerbContext& context);
VerbHandler declare_drivers(CLI::App& command, VerbContext& context);
VerbHandler declare_driver(CLI::App& command, VerbContext& context);
VerbHandler declare_assign(CLI::App& command, VerbContext& context);
VerbHandler declare_calibrate(CLI::App& command, VerbContext& context);

}  // namespace vibscore::client
