#pragma once
// Fork-join over the cores for the host's per-frame passes (packing, copying out, colour conversion,
// display encoding), on threads that exit when their range is done: the host's one threading model.
// Not OpenMP: libgomp's idle workers spin after every parallel region
// (GOMP_SPINCOUNT, 300,000 pauses by default: 10 to 14 ms of CPU per frame here, counted in
// /proc/<pid>/task/<tid>/schedstat), on the cores PoCL's workers need for the kernel launched next.
#include <algorithm>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace phongcl {

// body(part, begin, end) for `parts` contiguous ranges of [0, count), multiples of `grain` except the
// last, one per core (at most), part 0 on the calling thread. The first exception is rethrown.
template <typename Body>
void for_each_core_range(std::size_t count, std::size_t grain, const Body& body) {
  const std::size_t grains = (count + grain - 1) / grain;
  const std::size_t parts = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, std::max<std::size_t>(grains, 1));
  const std::size_t per_part = (grains + parts - 1) / parts * grain;
  std::vector<std::exception_ptr> errors(parts);
  auto run = [&](std::size_t part) {
    try {
      const std::size_t begin = std::min(count, part * per_part);
      body(part, begin, std::min(count, begin + per_part));
    } catch (...) {
      errors[part] = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> threads;
    for (std::size_t part = 1; part < parts; ++part) threads.emplace_back(run, part);
    run(0);
  }
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

}  // namespace phongcl
