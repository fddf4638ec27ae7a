#include "geometry/bvh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <stdexcept>
#include <string>

namespace phongcl {
namespace {

constexpr int kBins = 16;
// A ray's cost to visit a node (its two child boxes), in units of one item's intersection test.
constexpr double kTraversalCost = 1.0;

int ceil_log2(std::uint32_t count) { return count <= 1 ? 0 : std::bit_width(count - 1); }

struct Split {
  int axis = -1;  // -1: none found
  int last_left_bin = 0;
  double cost = std::numeric_limits<double>::infinity();  // in the units of kTraversalCost
};

class Builder {
 public:
  Builder(const std::vector<Box>& boxes, const std::vector<std::uint8_t>& groups, int max_depth)
      : boxes_(boxes), groups_(groups), max_depth_(max_depth) {
    centres_.reserve(boxes.size());
    for (const Box& box : boxes) centres_.push_back(box.centre());
  }

  Bvh build() {
    for (std::uint32_t i = 0; i < boxes_.size(); ++i)
      if (!boxes_[i].empty()) bvh_.order.push_back(i);
    if (bvh_.order.empty()) return std::move(bvh_);
    if (ceil_log2(static_cast<std::uint32_t>(bvh_.order.size())) > max_depth_)
      throw std::length_error("a BVH of " + std::to_string(bvh_.order.size()) + " items needs more than " +
                              std::to_string(max_depth_) + " levels");
    bvh_.nodes.reserve(2 * bvh_.order.size());
    bvh_.nodes.emplace_back();
    build_node(0, 0, static_cast<std::uint32_t>(bvh_.order.size()), 0);
    return std::move(bvh_);
  }

 private:
  // Invariant: depth + ceil_log2(end - begin) <= max_depth_, so that median splits from here on
  // would stay within max_depth_.
  void build_node(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth) {
    const std::uint32_t count = end - begin;
    Box box, centres;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.extend(boxes_[bvh_.order[i]]);
      centres.extend(centres_[bvh_.order[i]]);
    }
    bvh_.nodes[node].box = box;
    bvh_.depth = std::max(bvh_.depth, depth);
    if (count == 1) return make_leaf(node, begin, count);

    // The heuristic may split off a single item; allowed only while even that keeps the invariant.
    const bool heuristic_allowed = depth + 1 + ceil_log2(count - 1) <= max_depth_;
    const Split split = heuristic_allowed ? best_split(begin, end, box, centres) : Split{};
    if (count <= kBvhMaxLeafItems && one_group(begin, end) && count <= split.cost) return make_leaf(node, begin, count);

    std::uint32_t middle = begin;
    if (split.axis >= 0) {
      middle = static_cast<std::uint32_t>(
          std::partition(bvh_.order.begin() + begin, bvh_.order.begin() + end,
                         [&](std::uint32_t item) { return bin_of(centres_[item], centres, split.axis) <= split.last_left_bin; }) -
          bvh_.order.begin());
    } else {
      middle = median_split(begin, end, centres);
    }
    const auto children = static_cast<std::uint32_t>(bvh_.nodes.size());
    bvh_.nodes.emplace_back();
    bvh_.nodes.emplace_back();
    bvh_.nodes[node].first = children;
    bvh_.nodes[node].count = 0;
    build_node(children, begin, middle, depth + 1);
    build_node(children + 1, middle, end, depth + 1);
  }

  void make_leaf(std::uint32_t node, std::uint32_t begin, std::uint32_t count) {
    bvh_.nodes[node].first = begin;
    bvh_.nodes[node].count = count;
  }

  bool one_group(std::uint32_t begin, std::uint32_t end) const {
    for (std::uint32_t i = begin + 1; i < end; ++i)
      if (groups_[bvh_.order[i]] != groups_[bvh_.order[begin]]) return false;
    return true;
  }

  static int bin_of(const glm::dvec3& centre, const Box& centres, int axis) {
    const double extent = centres.hi[axis] - centres.lo[axis];
    const int bin = static_cast<int>(kBins * ((centre[axis] - centres.lo[axis]) / extent));
    return std::clamp(bin, 0, kBins - 1);
  }

  // The cheapest plane between bins on any axis: cost = traversal + (A_left N_left + A_right N_right) / A.
  Split best_split(std::uint32_t begin, std::uint32_t end, const Box& box, const Box& centres) const {
    Split best;
    const double area = box.half_area();
    for (int axis = 0; axis < 3; ++axis) {
      if (!(centres.hi[axis] > centres.lo[axis])) continue;
      std::array<Box, kBins> bin_boxes;
      std::array<std::uint32_t, kBins> bin_counts{};
      for (std::uint32_t i = begin; i < end; ++i) {
        const std::uint32_t item = bvh_.order[i];
        const int bin = bin_of(centres_[item], centres, axis);
        bin_boxes[bin].extend(boxes_[item]);
        ++bin_counts[bin];
      }
      // right_cost[b]: A N of bins b+1 ... kBins-1.
      std::array<double, kBins> right_cost{};
      Box right;
      std::uint32_t right_count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        right.extend(bin_boxes[b]);
        right_count += bin_counts[b];
        right_cost[b - 1] = right.half_area() * right_count;
      }
      Box left;
      std::uint32_t left_count = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        left.extend(bin_boxes[b]);
        left_count += bin_counts[b];
        if (left_count == 0 || left_count == end - begin) continue;
        const double cost = kTraversalCost + (left.half_area() * left_count + right_cost[b]) / area;
        if (cost < best.cost) best = {axis, b, cost};
      }
    }
    return best;
  }

  // Halves the range: items of one group before the other's when groups are mixed and the
  // centres coincide, else by centre along the widest axis.
  std::uint32_t median_split(std::uint32_t begin, std::uint32_t end, const Box& centres) {
    const auto first = bvh_.order.begin() + begin, last = bvh_.order.begin() + end;
    const glm::dvec3 extent = centres.hi - centres.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const auto middle = first + (last - first) / 2;
    std::nth_element(first, middle, last, [&](std::uint32_t a, std::uint32_t b) {
      if (groups_[a] != groups_[b]) return groups_[a] < groups_[b];
      return centres_[a][axis] < centres_[b][axis];
    });
    return static_cast<std::uint32_t>(middle - bvh_.order.begin());
  }

  const std::vector<Box>& boxes_;
  const std::vector<std::uint8_t>& groups_;
  std::vector<glm::dvec3> centres_;
  int max_depth_;
  Bvh bvh_;
};

}  // namespace

Bvh build_bvh(const std::vector<Box>& boxes, const std::vector<std::uint8_t>& groups, int max_depth) {
  return Builder(boxes, groups, max_depth).build();
}

}  // namespace phongcl
