#pragma once
// Mutual exclusion of crowdlab processes on one output folder (issue 21: two runs on one --out
// interleaved their writes, and both could exit 0 with a manifest whose hashes did not match the clips).
// Every command that writes an output folder takes it exclusively for its whole life: `run`, `demo`
// (its folder and the stimuli folder inside it, which `run --out DIR/stimuli` would write),
// `reproduce`, `experiment damping|manifold-compare|overlap-vs-density`, `analyze report`, `simulate-study`,
// `import-web` and `plan`. `export-web` needs none: it refuses any folder that is not empty, and a lock file
// would ship inside the web study.
//
// flock(2) on DIR/.crowdlab.lock, held until the process ends (the kernel drops it on exit or kill -9,
// so a crashed run never leaves a stale lock):
//   - a whole run and `--collect` take it exclusively;
//   - a shard (`--shard K/N`, N > 1) takes it shared, so the N shards of a Slurm array may run at once,
//     plus DIR/.crowdlab.shard-K-of-N.lock exclusively, so one shard never runs twice at once.
// The holder writes its pid into the lock file; the refusal names it.
#include <filesystem>
#include <string>

namespace crowdlab::cli {

class OutputFolderLock {
 public:
  /// Locks `dir` (created if missing) for a run of shard `shard_index` of `shard_count` (1 of 1 for an
  /// unsharded run or a collect). Throws InputError naming the folder and the other process's pid when
  /// another process holds a conflicting lock; never waits.
  OutputFolderLock(const std::filesystem::path& dir, int shard_index, int shard_count);
  /// Locks `dir` exclusively: a command that writes the whole folder.
  explicit OutputFolderLock(const std::filesystem::path& dir) : OutputFolderLock(dir, 1, 1) {}
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  int folder_fd_ = -1;
  int shard_fd_ = -1;
};

}  // namespace crowdlab::cli
