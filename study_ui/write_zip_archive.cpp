#include "study_ui/write_zip_archive.hpp"

#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "framework/core/error.hpp"
#include "study_ui/response_log.hpp"

namespace crowdlab::study {
namespace {

constexpr std::uint32_t kLocalHeaderSignature = 0x04034b50;
constexpr std::uint32_t kCentralHeaderSignature = 0x02014b50;
constexpr std::uint32_t kEndOfCentralDirectorySignature = 0x06054b50;
constexpr std::uint16_t kVersion = 20;             // 2.0: the version that introduced directories/stored
constexpr std::uint16_t kUtf8NamesFlag = 1 << 11;  // APPNOTE §4.4.4 bit 11
constexpr std::uint16_t kDosDate1980 = (0 << 9) | (1 << 5) | 1;  // 1980-01-01, time 00:00:00

void put16(std::string& out, std::uint32_t v) {
  out.push_back(static_cast<char>(v & 0xff));
  out.push_back(static_cast<char>((v >> 8) & 0xff));
}

void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xffff);
  put16(out, v >> 16);
}

std::string read_binary(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read (for the zip archive)");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void check_name(const std::string& name) {
  if (name.empty() || name.front() == '/' || name.find('\\') != std::string::npos ||
      name.find("..") != std::string::npos || name.size() > 0xffff)
    throw InputError("invalid name inside a zip archive: '" + name + "'");
}

/// The fields a local header and a central header share (APPNOTE §4.3.7 and §4.3.12, from "version
/// needed" to "extra field length").
void put_common_fields(std::string& out, const std::string& name, std::uint32_t crc, std::uint32_t size) {
  put16(out, kVersion);
  put16(out, kUtf8NamesFlag);
  put16(out, 0);  // method: stored
  put16(out, 0);  // time 00:00:00
  put16(out, kDosDate1980);
  put32(out, crc);
  put32(out, size);  // compressed size = size (stored)
  put32(out, size);
  put16(out, static_cast<std::uint32_t>(name.size()));
  put16(out, 0);  // extra field length
}

}  // namespace

void write_zip_archive(const std::string& zip_path, const std::vector<ZipEntry>& entries) {
  if (entries.size() > 0xffff) throw RuntimeError(zip_path + ": more than 65535 entries (no ZIP64)");
  std::string archive, central;
  for (const ZipEntry& e : entries) {
    check_name(e.name);
    const std::string data = read_binary(e.source_path);
    if (data.size() >= std::numeric_limits<std::uint32_t>::max() ||
        archive.size() + data.size() >= std::numeric_limits<std::uint32_t>::max())
      throw RuntimeError(zip_path + ": over 4 GiB (no ZIP64)");
    const auto size = static_cast<std::uint32_t>(data.size());
    const auto crc = static_cast<std::uint32_t>(
        crc32(0L, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size())));
    const auto offset = static_cast<std::uint32_t>(archive.size());

    put32(archive, kLocalHeaderSignature);
    put_common_fields(archive, e.name, crc, size);
    archive += e.name;
    archive += data;

    put32(central, kCentralHeaderSignature);
    put16(central, kVersion);  // version made by (MS-DOS attributes, i.e. none)
    put_common_fields(central, e.name, crc, size);
    put16(central, 0);  // file comment length
    put16(central, 0);  // disk number start
    put16(central, 0);  // internal attributes
    put32(central, 0);  // external attributes
    put32(central, offset);
    central += e.name;
  }
  const auto central_offset = static_cast<std::uint32_t>(archive.size());
  archive += central;
  put32(archive, kEndOfCentralDirectorySignature);
  put16(archive, 0);  // this disk
  put16(archive, 0);  // disk with the central directory
  put16(archive, static_cast<std::uint32_t>(entries.size()));
  put16(archive, static_cast<std::uint32_t>(entries.size()));
  put32(archive, static_cast<std::uint32_t>(central.size()));
  put32(archive, central_offset);
  put16(archive, 0);  // comment length
  write_file_atomically(zip_path, archive, false);
}

}  // namespace crowdlab::study
