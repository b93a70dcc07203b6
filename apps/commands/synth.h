// `wardmap synth`: render a synthetic hospital sequence with full ground truth.
#pragma once

#include <CLI/CLI.hpp>

namespace wardmap::apps {

// Adds the `synth` subcommand. Errors in the scenario or output folder surface as wardmap::InputError.
void add_synth_command(CLI::App& app);

}  // namespace wardmap::apps
