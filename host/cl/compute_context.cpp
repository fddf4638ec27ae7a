#include "cl/compute_context.h"

namespace phongcl {

ComputeContext make_compute_context(const Device& device) {
  cl::Context context(device.handle);
  cl::CommandQueue queue(context, device.handle, CL_QUEUE_PROFILING_ENABLE);
  return {device, context, queue};
}

double event_milliseconds(const cl::Event& event) {
  const auto start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  const auto end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return static_cast<double>(end - start) * 1e-6;
}

}  // namespace phongcl
