#pragma once
// Splitting a shot between processes: shard I of N shades the I-th, (I+N)-th, (I+2N)-th, ... frame of
// the ascending frame list (0-based), so every shard gets frames spread over the whole shot and the
// shards together shade every frame exactly once.
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace phongcl {

struct Shard {
  int index = 0, count = 1;
};

// "I/N" with 0 <= I < N; throws std::invalid_argument otherwise.
Shard parse_shard(const std::string& text);

// Inside a Slurm job array: I = (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN) / SLURM_ARRAY_TASK_STEP,
// N = SLURM_ARRAY_TASK_COUNT. Nothing outside an array; std::invalid_argument for an array whose
// task ids are not evenly spaced (--array=1,4,9), where I would not be a task's position.
// `getenv` is a parameter so tests need not change the process environment.
std::optional<Shard> shard_from_slurm(const std::function<const char*(const char*)>& getenv);

// The frames of `frames` (ascending) that `shard` shades.
std::vector<int> frames_of_shard(const std::vector<int>& frames, const Shard& shard);

}  // namespace phongcl
