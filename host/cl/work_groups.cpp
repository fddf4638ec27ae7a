#include "cl/work_groups.h"

namespace phongcl {

cl::NDRange spread_work_groups(const DeviceInfo& device, std::size_t items, std::size_t most) {
  if (!device.is_cpu || items == 0) return cl::NullRange;
  std::size_t size = 1;
  for (std::size_t candidate = 2; candidate <= most; ++candidate)
    if (items % candidate == 0) size = candidate;
  return cl::NDRange(size);
}

}  // namespace phongcl
