#pragma once
// Where a built program came from (cl/program_cache.h), without OpenCL's headers: the public API
// reports it (shading/shade_stats.h).

namespace phongcl {

enum class CacheOutcome { memory_hit, disk_hit, compiled };
const char* to_string(CacheOutcome outcome);  // "cache hit (memory)", "cache hit (disk)", "compiled"

}  // namespace phongcl
