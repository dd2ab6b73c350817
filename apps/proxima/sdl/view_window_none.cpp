// `proxima view` without SDL2 at build time: the command exists and says why it cannot run.
#include "../view_window.h"
#include "proxima/core/error.h"

namespace proxima::cli {

bool view_window_available() { return false; }

int run_view_window(ViewerSession&, const ViewWindowOptions&) {
  fail_input("view: this proxima was built without SDL2 (install libsdl2-dev and rebuild)");
}

}  // namespace proxima::cli
