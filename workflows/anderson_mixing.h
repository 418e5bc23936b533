// Anderson acceleration of a fixed-point iteration x = g(x) (Anderson, J. ACM 12:547, 1965; in the
// form of Walker & Ni, SIAM J. Numer. Anal. 49:1715, 2011, "Anderson acceleration for fixed-point
// iterations", type II with damping).
//
// With f_k = g(x_k) - x_k and the differences of the last m accepted iterates
//   dX = [x_{i+1} - x_i],  dF = [f_{i+1} - f_i]   (n x m_k, m_k <= m),
// the next iterate is
//   gamma   = argmin || f_k - dF gamma ||_2      (column-pivoting QR: rank-deficient dF is fine)
//   x_{k+1} = x_k + beta f_k - (dX + beta dF) gamma,
// which is plain damped iteration x_k + beta f_k while there is no history. The secant information
// in dF lets it converge where the plain iteration's error contracts slowly (an eigenvalue of the
// iteration matrix near 1).
#pragma once

#include <Eigen/Core>

#include <deque>

namespace tissuemesh {

class AndersonMixing {
 public:
  /// `memory`: differences kept (m >= 0; 0 is plain damped iteration).
  explicit AndersonMixing(int memory);

  /// The next iterate from the current accepted one `x` and its residual f = g(x) - x (same size,
  /// else std::invalid_argument). Records (x, f) for the next call's differences.
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& f, double beta);

  /// Forgets the history (e.g. after a step that was rejected): the next call is a plain step.
  void restart();

  /// Differences currently held.
  int history() const { return static_cast<int>(dX_.size()); }

 private:
  int memory_;
  std::deque<Eigen::VectorXd> dX_, dF_;
  Eigen::VectorXd last_x_, last_f_;
};

}  // namespace tissuemesh
