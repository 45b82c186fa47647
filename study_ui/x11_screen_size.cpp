#include "study_ui/x11_screen_size.hpp"

// Xlib last: its macros (Status, Bool, None) must not leak into other headers.
#include <X11/Xlib.h>

namespace crowdlab::study {

std::optional<std::pair<int, int>> x11_screen_size() {
  Display* display = XOpenDisplay(nullptr);
  if (display == nullptr) return std::nullopt;
  const int screen = DefaultScreen(display);
  const std::pair<int, int> size{DisplayWidth(display, screen), DisplayHeight(display, screen)};
  XCloseDisplay(display);
  if (size.first <= 0 || size.second <= 0) return std::nullopt;
  return size;
}

}  // namespace crowdlab::study
