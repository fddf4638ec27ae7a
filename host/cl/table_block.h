#pragma once
// Several tables in one device buffer, as ISPC's deferred example passes one header and offsets into
// one block of data: a kernel takes the block as one parameter and finds each table at its offset
// (in 4-byte words, among its scalars), so a new table is a new offset, not a new parameter. Tables
// start at multiples of an alignment; with the device's sub-buffer alignment, a kernel that fills or
// reads one table alone takes it as a sub-buffer.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

#include "cl/opencl.h"

namespace phongcl {

// The alignment of a sub-buffer's origin on `context`'s devices, in bytes (CL_DEVICE_MEM_BASE_ADDR_ALIGN).
std::size_t sub_buffer_alignment(const cl::Context& context);

class TableBlockLayout {
 public:
  // `alignment`: bytes, a multiple of 4.
  explicit TableBlockLayout(std::size_t alignment) : alignment_(alignment) {}

  // A table of host values, copied into the block; returns its offset in words. OpenCL has no empty
  // buffers and a table no empty extent: an empty table still gets a zeroed element, which no count
  // reaches.
  template <typename T>
  cl_uint add(const std::vector<T>& values) {
    static_assert(sizeof(T) % 4 == 0, "tables are counted in 4-byte words");
    const std::size_t bytes = std::max<std::size_t>(values.size(), 1) * sizeof(T);
    const cl_uint offset = reserve(bytes);
    host_.resize(starts_.back() + bytes);
    if (!values.empty()) std::memcpy(host_.data() + starts_.back(), values.data(), values.size() * sizeof(T));
    from_host_.back() = true;
    return offset;
  }
  // Room for `bytes` (at least one word) that a kernel fills; returns its offset in words.
  cl_uint reserve(std::size_t bytes);

  std::size_t bytes() const { return end_; }

  // The block in a new buffer with `flags`, the host tables copied in.
  cl::Buffer upload(const cl::Context& context, cl_mem_flags flags) const;
  // Copies the host tables into `block` (at least bytes() long), blocking.
  void write(cl::CommandQueue& queue, const cl::Buffer& block) const;
  // The table at word offset `offset` of `block` as a sub-buffer; alignment must be the device's.
  cl::Buffer table(const cl::Buffer& block, cl_uint offset) const;

 private:
  std::size_t alignment_;
  std::size_t end_ = 0;
  std::vector<std::size_t> starts_, sizes_;
  std::vector<bool> from_host_;
  std::vector<unsigned char> host_;  // the host tables' bytes at their places; reserved room past them is not kept
};

}  // namespace phongcl
