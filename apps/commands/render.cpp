// wardmap render-map: a PNG picture of a run's object map (map.glb), drawn with VTK.
#include <spdlog/spdlog.h>

#include <filesystem>
#include <memory>

#include "apps/commands/commands.h"
#include "apps/common.h"
#include "semantics/render/map_render.h"
#include "slam/core/errors.h"

namespace wardmap::apps {

namespace fs = std::filesystem;

namespace {

struct RenderArgs {
  std::string input, out, view = "top", title;
  int width = 1280, height = 960;
};

void render_map(const RenderArgs& a) {
  check_output_files({{a.out, "--out"}});
  const fs::path glb = file_or_run_file(a.input, "map.glb");
  // The file first (exit 2 on bad input), the display second.
  const semantics::MapScene scene = semantics::read_map_scene(glb);
  semantics::MapRenderOptions o;
  o.width = a.width;
  o.height = a.height;
  o.view = a.view == "oblique" ? semantics::MapView::Oblique : semantics::MapView::Top;
  o.title = a.title.empty() ? glb.string() : a.title;
  semantics::render_map_png(scene, a.out, o);
  size_t points = 0;
  for (const auto& p : scene.points) points += p.points.size();
  spdlog::info("render-map: {}, {}, {} -> {} ({}x{})", semantics::counted(scene.objects.size(), "object"),
               semantics::counted(scene.lines.size(), "trajectory line"), semantics::counted(points, "map point"),
               a.out, a.width, a.height);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto a = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand(
      "render-map",
      "Draw an object map (a run folder's map.glb, or any .glb) into a PNG: boxes in class colours\n"
      "with class labels, the trajectory, the map points, a ground grid, a legend of counts by class.\n"
      "Needs an X display (VTK); without one run it under a virtual display:\n"
      "  xvfb-run -a -s \"-screen 0 1280x1024x24\" wardmap render-map RUN_DIR --out map.png");
  cmd->add_option("map", a->input, "Run folder (uses its map.glb) or a .glb file")->required();
  cmd->add_option("--out", a->out, "PNG file to write")->required()->check(png_file());
  cmd->add_option("--width", a->width, "Picture width in pixels")->capture_default_str()->check(CLI::Range(16, 16384));
  cmd->add_option("--height", a->height, "Picture height in pixels")->capture_default_str()->check(CLI::Range(16, 16384));
  cmd->add_option("--view", a->view, "top (straight down, world x to the right) or oblique (from above and in front)")
      ->capture_default_str()
      ->check(CLI::IsMember({"top", "oblique"}));
  cmd->add_option("--title", a->title, "Text at the top left (default: the .glb path)");
  cmd->callback([a] { render_map(*a); });
}

}  // namespace wardmap::apps
