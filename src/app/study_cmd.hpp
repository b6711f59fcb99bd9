#pragma once
#include <string>
#include <vector>

namespace mdrmap::app {

/// `mdrmap study`: starts MPI itself (argc/argv are passed to MPI_Init).
int study_main(const std::vector<std::string>& args, int argc, char** argv);

/// The text of `mdrmap study --help`: the usage and the options in groups
/// (app/study_help.cpp, as the next two).
std::string study_help();

/// The text of `mdrmap study --help-all` (and `mdrmap help study`).
std::string study_help_all();

/// The text of `mdrmap help config`: the config keys the options override.
std::string study_config_help();

} // namespace mdrmap::app
