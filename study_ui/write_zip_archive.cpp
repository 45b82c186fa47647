#include "study_ui/write_zip_archive.hpp"

#include <sys/stat.h>
#include <zip.h>

#include <filesystem>
#include <memory>

#include "framework/core/error.hpp"

namespace crowdlab::study {
namespace {

constexpr zip_uint16_t kDosTime0000 = 0;                           // 00:00:00
constexpr zip_uint16_t kDosDate1980 = (0 << 9) | (1 << 5) | 1;     // 1980-01-01 (APPNOTE §4.4.6)
constexpr zip_uint32_t kRegularFile0644 = (S_IFREG | 0644) << 16;  // Unix mode in the high 16 bits

void check_name(const std::string& name) {
  if (name.empty() || name.front() == '/' || name.find('\\') != std::string::npos ||
      name.find("..") != std::string::npos || name.size() > 0xffff)
    throw InputError("invalid name inside a zip archive: '" + name + "'");
}

struct Discard {
  void operator()(zip_t* z) const { zip_discard(z); }
};

}  // namespace

void write_zip_archive(const std::string& zip_path, const std::vector<ZipEntry>& entries) {
  int code = 0;
  std::unique_ptr<zip_t, Discard> archive(zip_open(zip_path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code));
  if (!archive) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    const std::string what = zip_error_strerror(&error);
    zip_error_fini(&error);
    throw RuntimeError(zip_path + ": cannot create the zip archive: " + what);
  }
  zip_t* z = archive.get();
  auto fail = [&](const std::string& what) -> RuntimeError {
    return RuntimeError(zip_path + ": " + what + ": " + zip_strerror(z));
  };
  for (const ZipEntry& e : entries) {
    check_name(e.name);
    zip_source_t* source = nullptr;
    if (e.source_path.empty()) {
      source = zip_source_buffer(z, e.contents.data(), e.contents.size(), 0);  // kept alive by `entries`
    } else {
      if (!std::filesystem::is_regular_file(e.source_path))
        throw InputError(e.source_path + ": cannot read (for the zip archive)");
      source = zip_source_file(z, e.source_path.c_str(), 0, -1);
    }
    if (!source) throw fail("cannot read " + (e.source_path.empty() ? e.name : e.source_path));
    const zip_int64_t index = zip_file_add(z, e.name.c_str(), source, ZIP_FL_ENC_UTF_8);
    if (index < 0) {
      zip_source_free(source);
      if (zip_error_code_zip(zip_get_error(z)) == ZIP_ER_EXISTS)
        throw InputError("name twice inside a zip archive: '" + e.name + "'");
      throw fail("cannot add " + e.name);
    }
    const auto i = static_cast<zip_uint64_t>(index);
    if (zip_set_file_compression(z, i, ZIP_CM_STORE, 0) != 0 ||
        zip_file_set_dostime(z, i, kDosTime0000, kDosDate1980, 0) != 0 ||
        zip_file_set_external_attributes(z, i, 0, ZIP_OPSYS_UNIX, kRegularFile0644) != 0)
      throw fail("cannot set the attributes of " + e.name);
  }
  // zip_close writes a temporary file beside zip_path, renames it on success and frees the archive.
  if (zip_close(z) != 0) throw fail("cannot write the zip archive");
  archive.release();
}

}  // namespace crowdlab::study
