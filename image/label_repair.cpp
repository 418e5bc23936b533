// Why: two voxels of a tissue touching only along an edge or at a corner (or two voxels of the
// complement pinched by the tissue) would give edges shared by four triangles of one tissue or
// vertices joining two sheets. Unrestricted fixes can undo each other; here every change raises a
// voxel's region id, so the repair terminates (at most as many changes per voxel as there are
// regions):
//   - a region split inside a block is bridged by a lower-labelled voxel touching it, or else its
//     smallest piece joins its highest neighbouring region;
//   - a region pinching its complement gives one voxel to a higher neighbouring region, or else
//     the smallest (lower-labelled) piece of the complement is filled with the region.
// Passes repeat until none changes a voxel.
#include "image/label_repair.h"

#include "core/errors.h"

#include <array>
#include <algorithm>
#include <vector>

namespace tissuemesh {
namespace {

// Voxel b of a 2x2x2 block sits at (b & 1, (b >> 1) & 1, b >> 2); its face neighbours in the block
// are b ^ 1, b ^ 2, b ^ 4.

/// Face-connected components of each subset (bit mask) of the block's 8 voxels.
std::array<int, 256> component_counts() {
  std::array<int, 256> counts{};
  for (int mask = 0; mask < 256; ++mask) {
    int seen = 0, n = 0;
    for (int start = 0; start < 8; ++start) {
      if (!(mask >> start & 1) || (seen >> start & 1)) continue;
      ++n;
      int stack[8], top = 0;
      stack[top++] = start;
      seen |= 1 << start;
      while (top > 0) {
        const int b = stack[--top];
        for (int flip : {1, 2, 4}) {
          const int c = b ^ flip;
          if ((mask >> c & 1) && !(seen >> c & 1)) {
            seen |= 1 << c;
            stack[top++] = c;
          }
        }
      }
    }
    counts[mask] = n;
  }
  return counts;
}

const std::array<int, 256>& components() {
  static const std::array<int, 256> table = component_counts();
  return table;
}

int neighbours_in(int b, int mask) {
  return (mask >> (b ^ 1) & 1) + (mask >> (b ^ 2) & 1) + (mask >> (b ^ 4) & 1);
}

/// The block of lattice point (I, J, K): voxels (I-1..I, J-1..J, K-1..K), outside the image = 0.
struct Block {
  std::array<std::int32_t, 8> label{};
  std::array<long long, 8> index{};  ///< voxel index into the image, -1 for padding
  int I = 0, J = 0, K = 0;           ///< the lattice point

  void load(const LabelImage& img, int I_, int J_, int K_) {
    I = I_, J = J_, K = K_;
    for (int b = 0; b < 8; ++b) {
      const int i = I - 1 + (b & 1), j = J - 1 + (b >> 1 & 1), k = K - 1 + (b >> 2);
      const bool inside = i >= 0 && j >= 0 && k >= 0 && i < img.dims[0] && j < img.dims[1] && k < img.dims[2];
      index[b] = inside ? static_cast<long long>(img.index(i, j, k)) : -1;
      label[b] = inside ? img.labels[static_cast<std::size_t>(index[b])] : 0;
    }
  }
  bool uniform() const {
    for (int b = 1; b < 8; ++b)
      if (label[b] != label[0]) return false;
    return true;
  }
  int mask_of(std::int32_t a) const {
    int m = 0;
    for (int b = 0; b < 8; ++b)
      if (label[b] == a) m |= 1 << b;
    return m;
  }
};

/// Whether the block of lattice point (I, J, K) lies inside the image and holds one label: what
/// Block::load then uniform() would find, without the bounds checks (most blocks of an image are
/// inside one tissue; the first pass visits every block).
bool uniform_inside(const LabelImage& img, int I, int J, int K) {
  if (I < 1 || J < 1 || K < 1 || I >= img.dims[0] || J >= img.dims[1] || K >= img.dims[2]) return false;
  const std::size_t sy = static_cast<std::size_t>(img.dims[0]), sz = sy * static_cast<std::size_t>(img.dims[1]);
  const std::int32_t* p = img.labels.data() + img.index(I - 1, J - 1, K - 1);
  const std::int32_t l = p[0];
  return p[1] == l && p[sy] == l && p[sy + 1] == l && p[sz] == l && p[sz + 1] == l && p[sz + sy] == l &&
         p[sz + sy + 1] == l;
}

/// Lattice points whose block may hold a defect: all at first, then those with a voxel changed
/// since their block was last found sound. A block not marked is as it was when found sound, so a
/// pass that skips it does what a full pass would do there (nothing).
class DirtyBlocks {
 public:
  explicit DirtyBlocks(const std::array<int, 3>& dims)
      : nx_(dims[0] + 1), ny_(dims[1] + 1), flags_(static_cast<std::size_t>(nx_) * ny_ * (dims[2] + 1), 1) {}
  /// Whether (I, J, K) is marked; clears the mark.
  bool take(int I, int J, int K) {
    char& f = flags_[at(I, J, K)];
    const bool was = f != 0;
    f = 0;
    return was;
  }
  void mark(int I, int J, int K) { flags_[at(I, J, K)] = 1; }
  /// Voxel b of `block` changed: marks the eight blocks holding it.
  void mark_voxel(const Block& block, int b) {
    const int i = block.I - 1 + (b & 1), j = block.J - 1 + (b >> 1 & 1), k = block.K - 1 + (b >> 2);
    for (int dk = 0; dk < 2; ++dk)
      for (int dj = 0; dj < 2; ++dj)
        for (int di = 0; di < 2; ++di) mark(i + di, j + dj, k + dk);
  }
  bool any() const { return std::find(flags_.begin(), flags_.end(), 1) != flags_.end(); }

 private:
  std::size_t at(int I, int J, int K) const {
    return static_cast<std::size_t>(I) +
           static_cast<std::size_t>(nx_) * (static_cast<std::size_t>(J) + static_cast<std::size_t>(ny_) * static_cast<std::size_t>(K));
  }
  int nx_, ny_;
  std::vector<char> flags_;
};

/// First region of the block that is split, or whose complement is split, inside it; its mask in
/// `mask`. Returns false when every region of the block is well-composed here.
bool find_defect(const Block& block, int& mask) {
  const auto& comps = components();
  int done = 0;
  for (int b = 0; b < 8; ++b) {
    if (done >> b & 1) continue;
    const int m = block.mask_of(block.label[b]);
    done |= m;
    if (comps[m] > 1 || comps[~m & 255] > 1) {
      mask = m;
      return true;
    }
  }
  return false;
}

/// The face-connected components of `mask` inside the block, as masks, smallest first (ties: in
/// order of their first voxel).
std::vector<int> split(int mask) {
  std::vector<int> parts;
  int left = mask;
  while (left) {
    int part = left & -left, grown = 0;
    while (grown != part) {
      grown = part;
      for (int b = 0; b < 8; ++b)
        if (part >> b & 1)
          for (int flip : {1, 2, 4}) part |= (mask >> (b ^ flip) & 1) << (b ^ flip);
    }
    parts.push_back(part);
    left &= ~part;
  }
  std::stable_sort(parts.begin(), parts.end(), [](int a, int b) { return __builtin_popcount(a) < __builtin_popcount(b); });
  return parts;
}

void set_voxels(Block& block, int mask, std::int32_t label, LabelImage& img, std::size_t& changed, DirtyBlocks& dirty) {
  for (int b = 0; b < 8; ++b)
    if (mask >> b & 1) {
      block.label[b] = label;
      img.labels[static_cast<std::size_t>(block.index[b])] = label;
      dirty.mark_voxel(block, b);
      ++changed;
    }
}

bool in_image(const Block& block, int mask) {
  for (int b = 0; b < 8; ++b)
    if ((mask >> b & 1) && block.index[b] < 0) return false;
  return true;
}

/// Highest label among the face neighbours (inside the block) of `part` that are outside `mask`.
std::int32_t highest_neighbour(const Block& block, int part, int mask) {
  std::int32_t best = -1;
  for (int b = 0; b < 8; ++b)
    if (part >> b & 1)
      for (int flip : {1, 2, 4})
        if (!(mask >> (b ^ flip) & 1)) best = std::max(best, block.label[b ^ flip]);
  return best;
}

/// One relabelling that reduces the defect of region `mask`; every change raises a voxel's label,
/// which bounds the number of changes (termination). False when no such change exists.
bool fix_defect(Block& block, int mask, LabelImage& img, std::size_t& changed, DirtyBlocks& dirty) {
  const std::int32_t region = block.label[__builtin_ctz(static_cast<unsigned>(mask))];
  const int others = ~mask & 255;
  if (components()[mask] > 1) {
    // Bridge: a lower-labelled voxel touching the region joins it (most region neighbours first).
    int best = -1, best_score = 0;
    for (int b = 0; b < 8; ++b) {
      if (!(others >> b & 1) || block.index[b] < 0 || block.label[b] >= region) continue;
      const int score = neighbours_in(b, mask);
      if (score > best_score) best = b, best_score = score;
    }
    if (best >= 0) return set_voxels(block, 1 << best, region, img, changed, dirty), true;
    // Else the smallest piece of the region joins its highest neighbour (all neighbours are higher).
    for (int part : split(mask)) {
      const std::int32_t to = highest_neighbour(block, part, mask);
      if (to > region && in_image(block, part)) return set_voxels(block, part, to, img, changed, dirty), true;
    }
    return false;
  }
  // Pinch (the complement is split): a region voxel touching most other voxels takes the highest
  // neighbouring label above the region's ...
  int best = -1, best_score = 0;
  std::int32_t best_label = -1;
  for (int b = 0; b < 8; ++b) {
    if (!(mask >> b & 1) || block.index[b] < 0) continue;
    const std::int32_t to = highest_neighbour(block, 1 << b, mask);
    const int score = neighbours_in(b, others);
    if (to > region && score > best_score) best = b, best_score = score, best_label = to;
  }
  if (best >= 0) return set_voxels(block, 1 << best, best_label, img, changed, dirty), true;
  // ... else the smallest piece of the complement (all lower-labelled) is filled with the region.
  for (int part : split(others)) {
    bool lower = in_image(block, part);
    for (int b = 0; b < 8; ++b) lower = lower && (!(part >> b & 1) || block.label[b] < region);
    if (lower) return set_voxels(block, part, region, img, changed, dirty), true;
  }
  return false;
}

}  // namespace

LabelRepairResult make_well_composed(LabelImage& ids, int max_passes) {
  LabelRepairResult result;
  const auto& d = ids.dims;
  DirtyBlocks dirty(d);
  while (true) {
    if (result.passes >= max_passes)
      throw MeshingError("non-manifold voxel configurations remain after " + std::to_string(max_passes) +
                         " repair passes (" + std::to_string(result.relabelled_voxels) + " voxels relabelled)");
    ++result.passes;
    std::size_t changed = 0;
    Block block;
    for (int K = 0; K <= d[2]; ++K)
      for (int J = 0; J <= d[1]; ++J)
        for (int I = 0; I <= d[0]; ++I) {
          if (!dirty.take(I, J, K) || uniform_inside(ids, I, J, K)) continue;
          block.load(ids, I, J, K);
          if (block.uniform()) continue;
          int mask = 0;
          bool defect = false;
          for (int guard = 0; guard < 16 && (defect = find_defect(block, mask)); ++guard)
            if (!fix_defect(block, mask, ids, changed, dirty)) break;
          if (defect) dirty.mark(I, J, K);  // not (yet) repaired: the next pass looks again
        }
    result.relabelled_voxels += changed;
    if (changed == 0) break;
  }
  // After a pass without changes every block still marked holds a defect no change can fix, and
  // every other block is sound (what is_well_composed would find, without another pass).
  if (dirty.any())
    throw MeshingError("non-manifold voxel configurations at the image border cannot be repaired by relabelling");
  return result;
}

bool is_well_composed(const LabelImage& ids) {
  const auto& d = ids.dims;
  Block block;
  int mask = 0;
  for (int K = 0; K <= d[2]; ++K)
    for (int J = 0; J <= d[1]; ++J)
      for (int I = 0; I <= d[0]; ++I) {
        block.load(ids, I, J, K);
        if (!block.uniform() && find_defect(block, mask)) return false;
      }
  return true;
}

}  // namespace tissuemesh
