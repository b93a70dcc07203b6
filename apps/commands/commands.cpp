#include "apps/commands/commands.h"

#include "apps/commands/synth.h"

namespace wardmap::apps {

void register_commands(CLI::App& app) {
  add_info_command(app);
  add_eval_command(app);
  add_synth_command(app);
  add_run_command(app);
  add_eval_objects_command(app);
  add_compare_command(app);
  add_vocabulary_command(app);
  add_render_command(app);
}

}  // namespace wardmap::apps
