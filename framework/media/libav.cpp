#include "framework/media/libav.hpp"

#include <dlfcn.h>

#include <array>

#include "framework/core/error.hpp"

namespace crowdlab::media {
namespace {

/// dlopen's handle of lib<name>.so.<major>: RuntimeError with the loader's reason when it fails.
void* open_library(const std::string& name, int major) {
  const std::string soname = "lib" + name + ".so." + std::to_string(major);
  void* handle = ::dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = ::dlerror();
    throw RuntimeError("cannot load " + soname +
                       " (FFmpeg, needed to write and read videos): " + (why ? why : "unknown reason"));
  }
  return handle;
}

Libav load_libav() {
  // In dependency order: each library's own dependencies are loaded by dlopen.
  const std::array<void*, 4> handles = {
      open_library("avutil", LIBAVUTIL_VERSION_MAJOR), open_library("swscale", LIBSWSCALE_VERSION_MAJOR),
      open_library("avcodec", LIBAVCODEC_VERSION_MAJOR), open_library("avformat", LIBAVFORMAT_VERSION_MAJOR)};
  const auto find = [&handles](const char* name) {
    for (void* h : handles)
      if (void* f = ::dlsym(h, name)) return f;
    throw RuntimeError(std::string("FFmpeg's libraries lack the function ") + name);
  };
  Libav av;
#define CROWDLAB_LIBAV_RESOLVE(name) av.name = reinterpret_cast<decltype(av.name)>(find(#name));
  CROWDLAB_LIBAV_FUNCTIONS(CROWDLAB_LIBAV_RESOLVE)
#undef CROWDLAB_LIBAV_RESOLVE
  return av;
}

}  // namespace

const Libav& libav() {
  static const Libav table = load_libav();
  return table;
}

std::string libav_error(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {0};
  libav().av_strerror(code, buf, sizeof buf);
  return buf;
}

}  // namespace crowdlab::media
