#include "sequence/shard.h"

#include <regex>
#include <stdexcept>

namespace phongcl {

namespace {

int slurm_number(const std::function<const char*(const char*)>& getenv, const char* name, int fallback) {
  const char* value = getenv(name);
  if (value == nullptr || *value == '\0') return fallback;
  if (!std::regex_match(value, std::regex(R"(\d{1,9})")))
    throw std::invalid_argument(std::string(name) + "='" + value + "' is not a task number");
  return std::stoi(value);
}

}  // namespace

Shard parse_shard(const std::string& text) {
  std::smatch match;
  if (!std::regex_match(text, match, std::regex(R"((\d{1,9})/(\d{1,9}))")))
    throw std::invalid_argument("--shard '" + text + "': expected I/N, e.g. 0/4");
  const Shard shard{std::stoi(match[1].str()), std::stoi(match[2].str())};
  if (shard.count < 1 || shard.index >= shard.count)
    throw std::invalid_argument("--shard '" + text + "': I must be in 0..N-1 and N at least 1");
  return shard;
}

std::optional<Shard> shard_from_slurm(const std::function<const char*(const char*)>& getenv) {
  if (getenv("SLURM_ARRAY_TASK_ID") == nullptr) return std::nullopt;
  const int id = slurm_number(getenv, "SLURM_ARRAY_TASK_ID", 0);
  const int min = slurm_number(getenv, "SLURM_ARRAY_TASK_MIN", id);
  const int max = slurm_number(getenv, "SLURM_ARRAY_TASK_MAX", id);
  const int step = std::max(1, slurm_number(getenv, "SLURM_ARRAY_TASK_STEP", 1));
  const int count = slurm_number(getenv, "SLURM_ARRAY_TASK_COUNT", (max - min) / step + 1);
  if (id < min || (id - min) % step != 0 || (max - min) / step + 1 != count)
    throw std::invalid_argument("this Slurm job array's task ids are not evenly spaced (SLURM_ARRAY_TASK_ID=" +
                                std::to_string(id) + ", MIN=" + std::to_string(min) + ", MAX=" + std::to_string(max) +
                                ", STEP=" + std::to_string(step) + ", COUNT=" + std::to_string(count) +
                                "): give --shard I/N");
  return Shard{(id - min) / step, count};
}

std::vector<int> frames_of_shard(const std::vector<int>& frames, const Shard& shard) {
  std::vector<int> mine;
  for (std::size_t i = static_cast<std::size_t>(shard.index); i < frames.size(); i += static_cast<std::size_t>(shard.count))
    mine.push_back(frames[i]);
  return mine;
}

}  // namespace phongcl
