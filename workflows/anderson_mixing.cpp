#include "workflows/anderson_mixing.h"

#include <Eigen/QR>

#include <stdexcept>

namespace tissuemesh {

AndersonMixing::AndersonMixing(int memory) : memory_(memory) {
  if (memory < 0) throw std::invalid_argument("AndersonMixing: negative memory");
}

void AndersonMixing::restart() {
  dX_.clear();
  dF_.clear();
  last_x_.resize(0);
  last_f_.resize(0);
}

Eigen::VectorXd AndersonMixing::next(const Eigen::VectorXd& x, const Eigen::VectorXd& f, double beta) {
  if (x.size() != f.size()) throw std::invalid_argument("AndersonMixing: x and f differ in size");
  if (memory_ > 0 && last_x_.size() == x.size()) {
    dX_.push_back(x - last_x_);
    dF_.push_back(f - last_f_);
    if (static_cast<int>(dX_.size()) > memory_) {
      dX_.pop_front();
      dF_.pop_front();
    }
  }
  last_x_ = x;
  last_f_ = f;
  Eigen::VectorXd out = x + beta * f;
  if (dF_.empty()) return out;
  const Eigen::Index n = x.size(), m = static_cast<Eigen::Index>(dF_.size());
  Eigen::MatrixXd F(n, m), DX(n, m);
  for (Eigen::Index j = 0; j < m; ++j) {
    F.col(j) = dF_[j];
    DX.col(j) = dX_[j];
  }
  const Eigen::VectorXd gamma = F.colPivHouseholderQr().solve(f);
  out -= (DX + beta * F) * gamma;
  return out;
}

}  // namespace tissuemesh
