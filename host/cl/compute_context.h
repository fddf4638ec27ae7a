#pragma once
// A device with its context and an in-order, profiling-enabled queue.
#include "cl/device.h"
#include "cl/opencl.h"

namespace phongcl {

struct ComputeContext {
  Device device;
  cl::Context context;
  cl::CommandQueue queue;  // CL_QUEUE_PROFILING_ENABLE: kernel and transfer times come from events
};

ComputeContext make_compute_context(const Device& device);

// Milliseconds between an event's start and end (profiling info).
double event_milliseconds(const cl::Event& event);

}  // namespace phongcl
