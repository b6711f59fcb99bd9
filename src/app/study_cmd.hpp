#pragma once
#include <string>
#include <vector>

namespace mdrmap::app {

/// `mdrmap study`: starts MPI itself (argc/argv are passed to MPI_Init).
int study_main(const std::vector<std::string>& args, int argc, char** argv);
std::string study_help();

} // namespace mdrmap::app
