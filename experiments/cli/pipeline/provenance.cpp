#include "experiments/cli/pipeline/provenance.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <opencv2/core/version.hpp>
#include <sstream>

#include "crowdlab_version.hpp"
#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"

extern "C" {
#include <libavcodec/version.h>
#include <libavformat/version.h>
}

namespace crowdlab::cli {
namespace fs = std::filesystem;

std::string stage_input_hash(const std::string& stage, const nlohmann::json& params,
                             const std::vector<std::string>& upstream_hashes) {
  nlohmann::json j;
  j["stage"] = stage;
  j["params"] = params;  // nlohmann::json objects are key-sorted: the dump is canonical
  j["upstream"] = upstream_hashes;
  j["crowdlab_version"] = CROWDLAB_VERSION;
  return sha256_hex(j.dump());
}

static fs::path sidecar(const fs::path& output) {
  return fs::path(output.string() + ".prov.json");
}

std::string recorded_hash(const fs::path& output) {
  std::ifstream in(sidecar(output));
  if (!in) return "";
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    return j.value("input_hash", "");
  } catch (const nlohmann::json::exception&) {
    return "";  // a torn sidecar (killed mid-write) means "not up to date": the stage re-runs
  }
}

bool output_up_to_date(const fs::path& output, const std::string& input_hash) {
  return fs::exists(output) && recorded_hash(output) == input_hash;
}

nlohmann::json library_versions() {
  nlohmann::json j;
  j["crowdlab"] = CROWDLAB_VERSION;
  j["eigen"] = std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
               std::to_string(EIGEN_MINOR_VERSION);
  j["opencv"] = CV_VERSION;
  j["libavcodec"] = LIBAVCODEC_IDENT;
  j["libavformat"] = LIBAVFORMAT_IDENT;
  return j;
}

void write_file_atomic(const fs::path& path, const std::string& contents) {
  // Per-process temporary name: shards running at once may write the same file (e.g. spec.yaml).
  const fs::path tmp = path.string() + ".tmp." + std::to_string(::getpid());
  {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) throw RuntimeError(tmp.string() + ": cannot write");
    const char* p = contents.data();
    size_t left = contents.size();
    while (left > 0) {
      const ssize_t n = ::write(fd, p, left);
      if (n <= 0) {
        ::close(fd);
        throw RuntimeError(tmp.string() + ": write failed");
      }
      p += n;
      left -= static_cast<size_t>(n);
    }
    ::fsync(fd);
    ::close(fd);
  }
  fs::rename(tmp, path);
}

void record_provenance(const fs::path& output, const std::string& stage, const std::string& input_hash,
                       const ProvenanceContext& context) {
  nlohmann::json j;
  j["stage"] = stage;
  j["output"] = output.filename().string();
  j["input_hash"] = input_hash;
  j["crowdlab_version"] = CROWDLAB_VERSION;
  j["spec_hash"] = context.spec_hash;
  j["seed"] = context.seed;
  j["libraries"] = library_versions();
  const std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j["created_utc"] = buf;
  write_file_atomic(sidecar(output), j.dump(2) + "\n");
}

}  // namespace crowdlab::cli
