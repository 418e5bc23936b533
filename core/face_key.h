// A triangle's (or an edge's) identity independent of node order, packed in 64 bits for hash maps.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace tissuemesh {

/// Node ids must be below 2^21 (2,097,152); callers check mesh size before use.
constexpr std::size_t kMaxFaceKeyNodes = std::size_t{1} << 21;

inline std::uint64_t face_key(int a, int b, int c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 42) | (static_cast<std::uint64_t>(b) << 21) |
         static_cast<std::uint64_t>(c);
}

/// Any non-negative int node ids.
inline std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

/// The edge an edge_key() stands for: its node ids, the smaller first.
inline std::array<int, 2> edge_of_key(std::uint64_t key) {
  return {static_cast<int>(key >> 32), static_cast<int>(key & 0xffffffffu)};
}

}  // namespace tissuemesh
