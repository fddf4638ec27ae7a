#pragma once
// A device buffer kept from one frame to the next and grown only when a frame needs more, so
// repeated frames pack into memory that is already allocated and paged in.
#include <cstddef>

#include "cl/opencl.h"

namespace phongcl {

class ReusableBuffer {
 public:
  explicit ReusableBuffer(cl_mem_flags flags) : flags_(flags) {}

  // The buffer, reallocated when it holds fewer than `bytes`. Only call between frames: the
  // previous contents are not kept.
  const cl::Buffer& at_least(const cl::Context& context, std::size_t bytes) {
    if (bytes > capacity_) {
      buffer_ = cl::Buffer(context, flags_, bytes);
      capacity_ = bytes;
    }
    return buffer_;
  }

 private:
  cl_mem_flags flags_;
  cl::Buffer buffer_;
  std::size_t capacity_ = 0;
};

}  // namespace phongcl
