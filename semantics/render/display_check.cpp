// Is there an X display VTK can draw on? Kept apart from the VTK code: Xlib.h defines macros
// (Status, Bool, None, ...) that clash with other headers.
#include <cstdlib>

#include "semantics/render/map_render.h"

// Last: after Eigen, which refuses to compile once Xlib has defined Success.
#include <X11/Xlib.h>

namespace wardmap::semantics {

std::optional<std::string> display_problem() {
  static const char* const kAdvice =
      "VTK draws through X (Debian's VTK has no off-screen back-end); run under a virtual display: "
      "xvfb-run -a -s \"-screen 0 1280x1024x24\" wardmap render-map ...";
  // NOLINTNEXTLINE(concurrency-mt-unsafe): wardmap never calls setenv
  const char* name = std::getenv("DISPLAY");
  if (name == nullptr || *name == '\0') return std::string("no X display (DISPLAY is not set). ") + kAdvice;
  Display* d = XOpenDisplay(name);
  if (d == nullptr) return std::string("cannot open the X display '") + name + "'. " + kAdvice;
  XCloseDisplay(d);
  return std::nullopt;
}

}  // namespace wardmap::semantics
