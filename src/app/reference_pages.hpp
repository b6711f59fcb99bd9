#pragma once
// The generated reference pages beside docs/reference/cli.md: the study
// config's keys (docs/reference/config.md, from study/config_keys.hpp) and the
// map's groups and datasets (docs/reference/map-schema.md, from the
// declarations the map writer uses), printed by the hidden `mdrmap help
// --markdown config|map-schema`; and the keys as plain text for `mdrmap help
// config`.
#include <string>

namespace mdrmap::app {

/// docs/reference/config.md.
std::string config_reference_markdown();

/// Every config key, section by section, as help entries (mdrmap help config).
std::string config_keys_text();

/// docs/reference/map-schema.md.
std::string map_reference_markdown();

/// Its section "Output quantities": the output table (core/outputs/output_table.hpp).
std::string output_quantities_markdown();

} // namespace mdrmap::app
