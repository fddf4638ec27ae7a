#include "cl/table_block.h"

#include <algorithm>
#include <stdexcept>

namespace phongcl {

std::size_t sub_buffer_alignment(const cl::Context& context) {
  std::size_t alignment = 4;
  for (const cl::Device& device : context.getInfo<CL_CONTEXT_DEVICES>())
    alignment = std::max<std::size_t>(alignment, device.getInfo<CL_DEVICE_MEM_BASE_ADDR_ALIGN>() / 8);
  return alignment;
}

cl_uint TableBlockLayout::reserve(std::size_t bytes) {
  const std::size_t start = (end_ + alignment_ - 1) / alignment_ * alignment_;
  if (start / 4 > 0xffffffffu) throw std::runtime_error("a table block over 2^32 words");
  starts_.push_back(start);
  sizes_.push_back(std::max<std::size_t>(bytes, 4));
  from_host_.push_back(false);
  end_ = start + sizes_.back();
  return static_cast<cl_uint>(start / 4);
}

cl::Buffer TableBlockLayout::upload(const cl::Context& context, cl_mem_flags flags) const {
  std::vector<unsigned char> block(end_, 0);
  std::copy(host_.begin(), host_.end(), block.begin());
  return cl::Buffer(context, flags | CL_MEM_COPY_HOST_PTR, block.size(), block.data());
}

void TableBlockLayout::write(cl::CommandQueue& queue, const cl::Buffer& block) const {
  for (std::size_t t = 0; t < starts_.size(); ++t)
    if (from_host_[t]) queue.enqueueWriteBuffer(block, CL_FALSE, starts_[t], sizes_[t], host_.data() + starts_[t]);
  queue.finish();
}

cl::Buffer TableBlockLayout::table(const cl::Buffer& block, cl_uint offset) const {
  const std::size_t start = static_cast<std::size_t>(offset) * 4;
  const auto found = std::find(starts_.begin(), starts_.end(), start);
  if (found == starts_.end()) throw std::logic_error("no table starts at that offset");
  const cl_buffer_region region{start, sizes_[static_cast<std::size_t>(found - starts_.begin())]};
  cl::Buffer parent = block;  // cl.hpp's createSubBuffer is not const
  return parent.createSubBuffer(0, CL_BUFFER_CREATE_TYPE_REGION, &region);
}

}  // namespace phongcl
