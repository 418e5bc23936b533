// Why: corners never move, and the shape and intersection guards keep some edges far shorter than
// the size field asks for (two junction corners 0.7 mm apart where a small fgt island touches the
// skin, a curve edge at the rim of a thin sheet). Their neighbours are still sized by h(x), so a
// triangle with such an edge and two edges of length h has an angle of about (edge / h) radians:
// the worst triangles of a remeshed surface sit next to such edges unless the size is capped there.
#include "surface/graded_size_cap.h"

#include <cassert>
#include <cmath>
#include <limits>

namespace tissuemesh {

GradedSizeCap::GradedSizeCap(double factor, double gradation, const Eigen::AlignedBox3d& region)
    : factor_(factor), gradation_(gradation), region_(region) {
  assert(factor > 0.0 && gradation > 0.0 && !region.isEmpty());
}

void GradedSizeCap::add(const Eigen::Vector3d& m, double length, double largest) {
  const double size = factor_ * length, reach = (largest - size) / gradation_;
  if (!(reach > 0.0)) return;
  if (cell_ == 0.0) {
    // A cell of half the longest reach: each seed lands in at most 27 cells, a query reads one.
    cell_ = 0.5 * largest / gradation_;
    grid_.reset(cell_, region_);
  }
  const Eigen::Vector3d r = Eigen::Vector3d::Constant(reach);
  grid_.insert(static_cast<int>(seeds_.size()), Eigen::AlignedBox3d(m - r, m + r));
  seeds_.push_back({m, size});
}

double GradedSizeCap::operator()(const Eigen::Vector3d& p) const {
  double cap = std::numeric_limits<double>::infinity();
  if (seeds_.empty()) return cap;
  thread_local std::vector<int> found;  // per thread: queries may run on several at once
  found.clear();
  grid_.query(Eigen::AlignedBox3d(p, p), found);
  for (int i : found) cap = std::min(cap, seeds_[i].size + gradation_ * (p - seeds_[i].m).norm());
  return cap;
}

}  // namespace tissuemesh
