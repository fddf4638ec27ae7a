#pragma once
// check_materials (gbuffer.h) for a G-buffer that does not change, remembering the shortest table
// that has passed: a longer table only admits more indices, so it passes without a scan of every
// pixel (an interactive session checks the table of every edit of a drag).
#include <atomic>
#include <cstddef>
#include <limits>

#include "gbuffer/gbuffer.h"

namespace phongcl {

class MaterialCheck {
 public:
  // `passing_count`: a table length the G-buffer is known to pass with (default: none yet).
  explicit MaterialCheck(std::size_t passing_count = std::numeric_limits<std::size_t>::max())
      : smallest_passing_(passing_count) {}
  MaterialCheck(const MaterialCheck& other) : smallest_passing_(other.smallest_passing_.load()) {}
  MaterialCheck& operator=(const MaterialCheck& other) {
    smallest_passing_ = other.smallest_passing_.load();
    return *this;
  }

  // check_materials(gbuffer, material_count) unless a table at least this long passed on the same
  // G-buffer before. Safe to call from several threads at once.
  void check(const GBuffer& gbuffer, std::size_t material_count) const;

 private:
  mutable std::atomic<std::size_t> smallest_passing_;
};

}  // namespace phongcl
