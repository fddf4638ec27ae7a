#include "geometry/bvh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <exception>
#include <thread>
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

// Subtrees of more items than this are built on a thread of their own, while cores allow.
constexpr std::uint32_t kParallelItems = 1 << 16;

class Builder {
 public:
  // Builds into its own nodes; `order` is shared, each builder permuting its own range of it.
  Builder(const std::vector<Box>& boxes, const std::vector<std::uint8_t>& groups, const std::vector<glm::dvec3>& centres,
          std::vector<std::uint32_t>& order, int max_depth, int parallel_levels)
      : boxes_(boxes), groups_(groups), centres_(centres), order_(order), max_depth_(max_depth),
        parallel_levels_(parallel_levels) {}

  // The subtree over order[begin, end) at `depth`, its root at nodes()[0].
  void build(std::uint32_t begin, std::uint32_t end, int depth) {
    nodes_.reserve(2 * (end - begin));
    nodes_.emplace_back();
    build_node(0, begin, end, depth);
  }
  std::vector<Bvh::Node>& nodes() { return nodes_; }
  int depth() const { return depth_; }

 private:
  // Invariant: depth + ceil_log2(end - begin) <= max_depth_, so that median splits from here on
  // would stay within max_depth_.
  void build_node(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth) {
    const std::uint32_t count = end - begin;
    Box box, centres;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.extend(boxes_[order_[i]]);
      centres.extend(centres_[order_[i]]);
    }
    nodes_[node].box = box;
    depth_ = std::max(depth_, depth);
    if (count == 1) return make_leaf(node, begin, count);

    // The heuristic may split off a single item; allowed only while even that keeps the invariant.
    const bool heuristic_allowed = depth + 1 + ceil_log2(count - 1) <= max_depth_;
    const Split split = heuristic_allowed ? best_split(begin, end, box, centres) : Split{};
    if (count <= kBvhMaxLeafItems && one_group(begin, end) && count <= split.cost) return make_leaf(node, begin, count);

    std::uint32_t middle = begin;
    if (split.axis >= 0) {
      middle = static_cast<std::uint32_t>(
          std::partition(order_.begin() + begin, order_.begin() + end,
                         [&](std::uint32_t item) { return bin_of(centres_[item], centres, split.axis) <= split.last_left_bin; }) -
          order_.begin());
    } else {
      middle = median_split(begin, end, centres);
    }
    const auto children = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    nodes_[node].first = children;
    nodes_[node].count = 0;
    if (parallel_levels_ > 0 && end - middle >= kParallelItems) {
      // The second subtree on another thread, into nodes of its own grafted on afterwards.
      Builder second(boxes_, groups_, centres_, order_, max_depth_, parallel_levels_ - 1);
      std::exception_ptr failure;
      std::thread worker([&] {
        try {
          second.build(middle, end, depth + 1);
        } catch (...) {
          failure = std::current_exception();
        }
      });
      --parallel_levels_;
      build_node(children, begin, middle, depth + 1);
      ++parallel_levels_;
      worker.join();
      if (failure) std::rethrow_exception(failure);
      graft(children + 1, second);
      return;
    }
    build_node(children, begin, middle, depth + 1);
    build_node(children + 1, middle, end, depth + 1);
  }

  // `other`'s root becomes nodes_[slot] and its other nodes follow ours, their links renumbered.
  void graft(std::uint32_t slot, Builder& other) {
    std::vector<Bvh::Node>& grafted = other.nodes();
    const auto base = static_cast<std::uint32_t>(nodes_.size()) - 1;  // local index k >= 1 lands at base + k
    for (Bvh::Node& node : grafted)
      if (!node.leaf()) node.first += base;
    nodes_[slot] = grafted[0];
    nodes_.insert(nodes_.end(), grafted.begin() + 1, grafted.end());
    depth_ = std::max(depth_, other.depth());
  }

  void make_leaf(std::uint32_t node, std::uint32_t begin, std::uint32_t count) {
    nodes_[node].first = begin;
    nodes_[node].count = count;
  }

  bool one_group(std::uint32_t begin, std::uint32_t end) const {
    for (std::uint32_t i = begin + 1; i < end; ++i)
      if (groups_[order_[i]] != groups_[order_[begin]]) return false;
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
        const std::uint32_t item = order_[i];
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
    const auto first = order_.begin() + begin, last = order_.begin() + end;
    const glm::dvec3 extent = centres.hi - centres.lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const auto middle = first + (last - first) / 2;
    std::nth_element(first, middle, last, [&](std::uint32_t a, std::uint32_t b) {
      if (groups_[a] != groups_[b]) return groups_[a] < groups_[b];
      return centres_[a][axis] < centres_[b][axis];
    });
    return static_cast<std::uint32_t>(middle - order_.begin());
  }

  const std::vector<Box>& boxes_;
  const std::vector<std::uint8_t>& groups_;
  const std::vector<glm::dvec3>& centres_;
  std::vector<std::uint32_t>& order_;
  int max_depth_;
  int parallel_levels_;
  std::vector<Bvh::Node> nodes_;
  int depth_ = 0;
};

}  // namespace

Bvh build_bvh(const std::vector<Box>& boxes, const std::vector<std::uint8_t>& groups, int max_depth) {
  Bvh bvh;
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    if (!boxes[i].empty()) bvh.order.push_back(i);
  if (bvh.order.empty()) return bvh;
  if (ceil_log2(static_cast<std::uint32_t>(bvh.order.size())) > max_depth)
    throw std::length_error("a BVH of " + std::to_string(bvh.order.size()) + " items needs more than " +
                            std::to_string(max_depth) + " levels");
  std::vector<glm::dvec3> centres;
  centres.reserve(boxes.size());
  for (const Box& box : boxes) centres.push_back(box.centre());
  // One more thread per level while cores last: 2 cores, one level.
  const int parallel_levels = std::bit_width(std::max(1u, std::thread::hardware_concurrency())) - 1;
  Builder builder(boxes, groups, centres, bvh.order, max_depth, parallel_levels);
  builder.build(0, static_cast<std::uint32_t>(bvh.order.size()), 0);
  bvh.nodes = std::move(builder.nodes());
  bvh.depth = builder.depth();
  return bvh;
}

}  // namespace phongcl
