#pragma once
// Work-group sizes for kernels whose work-items are long and uneven.
#include <cstddef>

#include "cl/device_info.h"
#include "cl/opencl.h"

namespace phongcl {

// The local size for `items` work-items that each do much work, and unequal amounts of it (a row of
// pixels through its tile's lights, a block of tiles through its candidate lights). On a CPU device
// a work-group runs on one core from its first work-item to its last, and PoCL's default made a
// few large groups, so a core sat idle while the other finished the slowest: there it is the
// largest divisor of `items` up to `most`, many groups for the cores to share. Elsewhere (GPUs) it
// is the runtime's choice.
cl::NDRange spread_work_groups(const DeviceInfo& device, std::size_t items, std::size_t most);

}  // namespace phongcl
