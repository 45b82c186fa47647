#pragma once
// x11_screen_size: the size of the X server's default screen, asked of the X server itself (Xlib),
// for a study window that must cover the screen when no window manager applies full screen (a bare
// X server such as Xvfb, or a kiosk session): OpenCV highgui exposes no screen size.
#include <optional>
#include <utility>

namespace crowdlab::study {

/// {width, height} in pixels of the default screen of $DISPLAY, or nullopt when there is no X
/// server to ask (no DISPLAY, Wayland without XWayland, connection refused).
std::optional<std::pair<int, int>> x11_screen_size();

}  // namespace crowdlab::study
