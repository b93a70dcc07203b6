// wardmap: semantic object SLAM for service robots. One executable, one sub-command per job.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "apps/commands/commands.h"
#include "apps/interrupt.h"
#include "slam/core/errors.h"

namespace {

int run(int argc, char** argv) {
  CLI::App app{
      "wardmap: semantic object SLAM for hospital service robots.\n"
      "Give it a camera sequence (TUM RGB-D, KITTI odometry, EuRoC, 7-Scenes, an image folder or a video);\n"
      "it gives back the trajectory, a sparse map and a map of the objects, and evaluates them against\n"
      "ground truth. Run 'wardmap <command> --help' for each command."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "wardmap 0.1.0");
  bool verbose = false, quiet = false;
  app.add_flag("-v,--verbose", verbose, "More log output (debug level)");
  app.add_flag("-q,--quiet", quiet, "Only warnings and errors");

  wardmap::apps::register_commands(app);

  auto logger = spdlog::stderr_color_mt("wardmap");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("[%H:%M:%S] [%^%l%$] %v");
  app.parse_complete_callback([&] {
    spdlog::set_level(verbose ? spdlog::level::debug : quiet ? spdlog::level::warn : spdlog::level::info);
  });

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;  // usage errors exit like bad input
  } catch (const wardmap::apps::Interrupted& e) {
    std::fprintf(stderr, "wardmap: %s\n", e.what());
    return 128 + e.signal();  // as a shell reports a process ended by that signal
  } catch (const wardmap::InputError& e) {
    std::fprintf(stderr, "wardmap: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wardmap: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // run() reports every error of a command itself; this is for what escapes its set-up (out of memory).
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wardmap: error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "wardmap: error: unknown exception\n");
  }
  return 1;
}
