// The sub-commands of the wardmap executable; each file under apps/commands adds one.
#pragma once

#include <CLI/CLI.hpp>

namespace wardmap::apps {

void register_commands(CLI::App& app);

void add_info_command(CLI::App& app);
void add_eval_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_eval_objects_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_vocabulary_command(CLI::App& app);
void add_render_command(CLI::App& app);

}  // namespace wardmap::apps
