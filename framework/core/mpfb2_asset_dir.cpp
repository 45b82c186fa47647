#include "framework/core/mpfb2_asset_dir.hpp"

#include <cstdlib>

#include "crowdlab_shipped_mpfb2_dir.hpp"

namespace crowdlab {

std::filesystem::path shipped_mpfb2_dir() {
  return CROWDLAB_SHIPPED_MPFB2_DIR;
}

std::filesystem::path default_mpfb2_dir() {
  const char* env = std::getenv("CROWDLAB_MPFB2");
  return env && *env ? std::filesystem::path(env) : shipped_mpfb2_dir();
}

std::filesystem::path default_makehuman_dir() {
  const char* env = std::getenv("CROWDLAB_MAKEHUMAN");
  return env && *env ? std::filesystem::path(env) : std::filesystem::path(CROWDLAB_SHIPPED_MAKEHUMAN_DIR);
}

}  // namespace crowdlab
