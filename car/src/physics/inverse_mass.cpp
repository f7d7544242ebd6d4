// The joint-space mass matrix of a Bullet multibody, built from Bullet's cached frames and factored (inverse_mass.hpp).
#include "inverse_mass.hpp"

#include <cmath>
#include <utility>

namespace car_sim {
namespace physics {

namespace {

// Cholesky of the m x m matrix in l (row major, lower triangle), in place: M = L L^T; inv: 1 / L's diagonal. false
// if M is not positive definite. M > 0: m known at compile time (the same operations in the same order).
template <int M>
inline bool cholesky(double* l, double* inv, int m) {
  if (M > 0) m = M;
  for (int j = 0; j < m; ++j) {
    double* rj = l + static_cast<size_t>(j) * m;
    double d = rj[j];
#pragma GCC unroll 16
    for (int k = 0; k < j; ++k) d -= rj[k] * rj[k];
    if (!(d > 0.0)) return false;
    d = std::sqrt(d);
    rj[j] = d;
    for (int i = j + 1; i < m; ++i) {
      double* ri = l + static_cast<size_t>(i) * m;
      double s = ri[j];
#pragma GCC unroll 16
      for (int k = 0; k < j; ++k) s -= ri[k] * rj[k];
      ri[j] = s / d;
    }
  }
  for (int j = 0; j < m; ++j) inv[j] = 1.0 / l[static_cast<size_t>(j) * m + j];
  return true;
}

}  // namespace

template <class F>
void InverseMass::for_each_dof_above(int link, const btVector3& p, F&& f) const {
  for (int j = link; j >= 0; j = mb_->getLink(j).m_parent) {
    const btMultibodyLink& l = mb_->getLink(j);
    const btVector3 r = p - com_[j + 1];
    for (int d = 0; d < l.m_dofCount; ++d) {
      const int k = l.m_dofOffset + d;
      f(k, top_[k], bottom_[k] + top_[k].cross(r));
    }
  }
}

bool InverseMass::build(const btMultiBody& mb) {
  mb_ = &mb;
  const int links = mb.getNumLinks();
  n_ = 6 + mb.getNumDofs();
  if (mb.isBaseKinematic() || mb.isUsingGlobalVelocities()) return false;
  for (int i = 0; i < links; ++i)
    if (mb.isLinkKinematic(i)) return false;
  // a static base does not move (Bullet's pass gives it no acceleration): its rows are left out
  const bool fixed = mb.isBaseStaticOrKinematic();
  off_ = fixed ? 6 : 0;
  const int m = n_ - off_;
  l_.assign(static_cast<size_t>(m) * m, 0.0);

  // Frames of the bodies: rotation frame -> world and centre of mass [m], world frame. Bullet's base frame sits at
  // the base's centre of mass; link i's at its own, m_cachedRVector (frame i) from its parent's.
  const int bodies = links + 1;
  rot_.resize(bodies);
  com_.resize(bodies);
  rot_[0] = btMatrix3x3(mb.getWorldToBaseRot()).transpose();
  com_[0] = mb.getBasePos();
  for (int i = 0; i < links; ++i) {
    const btMultibodyLink& l = mb.getLink(i);
    const int p = l.m_parent + 1;
    // m_cachedRotParentToThis turns parent-frame vectors into frame i:
    // frame i -> world = (parent -> world) * its inverse
    rot_[i + 1] = rot_[p] * btMatrix3x3(l.m_cachedRotParentToThis).transpose();
    com_[i + 1] = com_[p] + rot_[i + 1] * l.m_cachedRVector;
  }

  // M = sum over bodies of J_b^T diag(m_b, I_b world) J_b, J_b: the body's angular velocity w and centre-of-mass
  // velocity u per generalised velocity. A base rotation w = e moves the body's centre of mass by e x r (r from the
  // base's), a base translation by e; so the base block is sum (I_w + m [r]x^T [r]x, m [r]x; m 1), and a joint
  // column u, w meets the base's with m r x u + I_w w (rotation) and m u (translation). Only the joints of the
  // body and its ancestors move it.
  w_.resize(n_);
  u_.resize(n_);
  cols_.resize(n_);
  iw_.resize(bodies);
  top_.resize(n_ - 6);
  bottom_.resize(n_ - 6);
  one_dof_joints_ = true;
  for (int i = 0; i < links; ++i) {
    const btMultibodyLink& l = mb.getLink(i);
    if (l.m_dofCount > 1) one_dof_joints_ = false;
    for (int d = 0; d < l.m_dofCount; ++d) {
      top_[l.m_dofOffset + d] = rot_[i + 1] * l.m_axes[d].m_topVec;
      bottom_[l.m_dofOffset + d] = rot_[i + 1] * l.m_axes[d].m_bottomVec;
    }
  }
  double* M = l_.data();
  // M's entry (row, col), row >= col, in the full 6 + dofs layout
  auto at = [&](int row, int col) -> double& { return M[static_cast<size_t>(row - off_) * m + (col - off_)]; };
  // the base block's sums over the bodies: mass [kg], first moment about the base's centre of mass [kg m], inertia
  // about it [kg m^2] (lower triangle)
  double total = 0;
  btVector3 moment(0, 0, 0);
  double inertia_sum[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int b = 0; b < bodies; ++b) {
    if (b == 0 && fixed) continue;
    const btScalar mass = b == 0 ? mb.getBaseMass() : mb.getLink(b - 1).m_mass;
    const btVector3& inertia = b == 0 ? mb.getBaseInertia() : mb.getLink(b - 1).m_inertiaLocal;
    // inertia about the centre of mass, world frame
    const btMatrix3x3& R = rot_[b];
    iw_[b] = R.scaled(inertia) * R.transpose();
    const btMatrix3x3& iw = iw_[b];
    // the joints from the body up to the base: a unit rate of dof d of link j turns the body with a_d about link
    // j's centre of mass and moves that point with b_d (Bullet's spatial axis, frame j); columns in decreasing order
    int k = 0;
    for_each_dof_above(b - 1, com_[b], [&](int dof, const btVector3& a, const btVector3& u) {
      cols_[k] = 6 + dof;
      w_[k] = a;
      u_[k] = u;
      ++k;
    });
    const btVector3 r = com_[b] - com_[0];
    for (int p = 0; p < k; ++p) {
      const btVector3 iwp = iw * w_[p];
      for (int q = 0; q < k; ++q)
        if (cols_[q] <= cols_[p]) at(cols_[p], cols_[q]) += mass * u_[p].dot(u_[q]) + iwp.dot(w_[q]);
      if (!fixed) {
        const btVector3 rot = mass * r.cross(u_[p]) + iwp;
        for (int a = 0; a < 3; ++a) {
          at(cols_[p], a) += rot[a];
          at(cols_[p], 3 + a) += mass * u_[p][a];
        }
      }
    }
    if (!fixed) {
      const double rr = r.length2();
      total += mass;
      moment += mass * r;
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c <= a; ++c) inertia_sum[a][c] += iw[a][c] + mass * ((a == c ? rr : 0.0) - r[a] * r[c]);
    }
  }
  if (!fixed) {
    for (int a = 0; a < 3; ++a) {
      for (int c = 0; c <= a; ++c) at(a, c) = inertia_sum[a][c];
      btVector3 e(0, 0, 0);
      e[a] = 1;
      // M[v_c, w_a] = sum m (e_a x r)_c
      const btVector3 exr = e.cross(moment);
      for (int c = 0; c < 3; ++c) at(3 + c, a) = exr[c];
      at(3 + a, 3 + a) = total;
    }
  }

  // Cholesky, in place: M = L L^T
  inv_diag_.resize(m);
  switch (m) {
    case 7: return cholesky<7>(l_.data(), inv_diag_.data(), m);
    case 8: return cholesky<8>(l_.data(), inv_diag_.data(), m);
    case 9: return cholesky<9>(l_.data(), inv_diag_.data(), m);
    case 10: return cholesky<10>(l_.data(), inv_diag_.data(), m);
    case 11: return cholesky<11>(l_.data(), inv_diag_.data(), m);
    case 12: return cholesky<12>(l_.data(), inv_diag_.data(), m);
    default: return cholesky<0>(l_.data(), inv_diag_.data(), m);
  }
}

namespace {

// L y = f, then L^T x = y in place (x = y), L lower triangular m x m, row major; inv: 1 / its diagonal. M > 0: m
// known at compile time (the loops unrolled, the same operations in the same order as M = 0, which takes m).
template <int M>
inline void triangular_solves(const double* l, const double* inv, const double* f, double* y, int m) {
  if (M > 0) m = M;
  // L y = f
#pragma GCC unroll 16
  for (int i = 0; i < m; ++i) {
    const double* ri = l + static_cast<size_t>(i) * m;
    double s = f[i];
#pragma GCC unroll 16
    for (int k = 0; k < i; ++k) s -= ri[k] * y[k];
    y[i] = s * inv[i];
  }
  // L^T x = y, by columns of L: once x_i is known, take its share out of the rows above
#pragma GCC unroll 16
  for (int i = m - 1; i >= 0; --i) {
    const double* ri = l + static_cast<size_t>(i) * m;
    const double xi = y[i] * inv[i];
    y[i] = xi;
#pragma GCC unroll 16
    for (int k = 0; k < i; ++k) y[k] -= ri[k] * xi;
  }
}

}  // namespace

void InverseMass::solve(const btScalar* f, btScalar* x) const {
  const int m = n_ - off_;
  for (int i = 0; i < off_; ++i) x[i] = 0;
  btScalar* y = x + off_;
  const double* l = l_.data();
  const double* inv = inv_diag_.data();
  // the common sizes (a floating base with 1 to 6 joints) with the size known to the compiler
  switch (m) {
    case 7: return triangular_solves<7>(l, inv, f + off_, y, m);
    case 8: return triangular_solves<8>(l, inv, f + off_, y, m);
    case 9: return triangular_solves<9>(l, inv, f + off_, y, m);
    case 10: return triangular_solves<10>(l, inv, f + off_, y, m);
    case 11: return triangular_solves<11>(l, inv, f + off_, y, m);
    case 12: return triangular_solves<12>(l, inv, f + off_, y, m);
    default: return triangular_solves<0>(l, inv, f + off_, y, m);
  }
}

bool InverseMass::contact_jacobian(int link, const btVector3& p, const btVector3& n, btScalar* jac) const {
  if (!one_dof_joints_) return false;
  // the base's rotation about its centre of mass moves p with w x (p - c0); its translation with v
  const btVector3 w = (p - com_[0]).cross(n);
  for (int a = 0; a < 3; ++a) {
    jac[a] = w[a];
    jac[3 + a] = n[a];
  }
  for (int i = 6; i < n_; ++i) jac[i] = 0;
  // a joint of the link or an ancestor moves p with u
  for_each_dof_above(link, p, [&](int k, const btVector3&, const btVector3& u) { jac[6 + k] = n.dot(u); });
  return true;
}

bool InverseMass::free_motion_supported(const btMultiBody& mb) {
  for (int i = 0; i < mb.getNumLinks(); ++i) {
    const btMultibodyLink& l = mb.getLink(i);
    if (l.m_jointFeedback) return false;
    if (l.m_jointType != btMultibodyLink::eRevolute && l.m_jointType != btMultibodyLink::ePrismatic &&
        l.m_jointType != btMultibodyLink::eFixed)
      return false;
  }
  return true;
}

void InverseMass::free_acceleration(const btMultiBody& mb, btScalar* qdd) {
  const int links = mb.getNumLinks();
  const int bodies = links + 1;
  const bool fixed = off_ == 6;
  omega_.resize(bodies);
  vel_.resize(bodies);
  alpha_.resize(bodies);
  acc_.resize(bodies);
  force_.assign(n_, 0.0);
  // Velocities and their rates with every joint acceleration zero, base first (world frame; a body's point is its
  // centre of mass). Over a joint, seen from the parent: the child turns at w_rel and its centre moves at v_rel
  // (Bullet's spatial axes times the rates); from the world, the parent's rotation adds w_p x d to the centre's
  // velocity and the usual transport terms to its acceleration, 2 w_p x v_rel (Coriolis) and w_rel x v_rel (the
  // turn about the joint's axis, zero for a slider).
  omega_[0] = mb.getBaseOmega();
  vel_[0] = mb.getBaseVel();
  alpha_[0].setZero();
  acc_[0].setZero();
  for (int i = 0; i < links; ++i) {
    const btMultibodyLink& l = mb.getLink(i);
    const int p = l.m_parent + 1, c = i + 1;
    const btScalar* qd = mb.getJointVelMultiDof(i);
    btVector3 w_rel(0, 0, 0), v_rel(0, 0, 0);
    for (int d = 0; d < l.m_dofCount; ++d) {
      w_rel += top_[l.m_dofOffset + d] * qd[d];
      v_rel += bottom_[l.m_dofOffset + d] * qd[d];
      // the joint's effort [N m or N]
      force_[6 + l.m_dofOffset + d] = l.m_jointTorque[d];
    }
    const btVector3 d = com_[c] - com_[p];
    const btVector3& wp = omega_[p];
    const btVector3 wxd = wp.cross(d);
    omega_[c] = wp + w_rel;
    vel_[c] = vel_[p] + wxd + v_rel;
    alpha_[c] = alpha_[p] + wp.cross(w_rel);
    acc_[c] = acc_[p] + alpha_[p].cross(d) + wp.cross(wxd) + btScalar(2) * wp.cross(v_rel) + w_rel.cross(v_rel);
  }
  // Each body's wrench about its centre of mass, world frame, to hold that motion against what acts on it: m a and
  // I alpha + w x I w (Bullet's gyroscopic term), Bullet's damping (k1 + k2 |v|) m v and (k1 + k2 |w|) I w, less
  // the applied force and torque (gravity among them, applyGravity). Its share of each generalised force: the
  // columns build() sums M from.
  const btScalar k_lin = mb.getLinearDamping(), k_ang = mb.getAngularDamping();
  const bool gyro = mb.getUseGyroTerm();
  for (int b = 0; b < bodies; ++b) {
    if (b == 0 && fixed) continue;
    const btScalar mass = b == 0 ? mb.getBaseMass() : mb.getLink(b - 1).m_mass;
    const btMatrix3x3& iw = iw_[b];
    const btVector3& w = omega_[b];
    const btVector3 iww = iw * w;
    btVector3 f = mass * acc_[b] - (b == 0 ? mb.getBaseForce() : mb.getLinkForce(b - 1));
    btVector3 n = iw * alpha_[b] - (b == 0 ? mb.getBaseTorque() : mb.getLinkTorque(b - 1));
    if (gyro) n += w.cross(iww);
    if (k_lin != 0) f += mass * vel_[b] * (k_lin + k_lin * vel_[b].safeNorm());
    if (k_ang != 0) n += iww * (k_ang + k_ang * w.safeNorm());
    for_each_dof_above(b - 1, com_[b], [&](int k, const btVector3& a, const btVector3& u) {
      force_[6 + k] -= u.dot(f) + a.dot(n);
    });
    if (!fixed) {
      // the base's rotation about its centre of mass and its translation
      const btVector3 t = n + (com_[b] - com_[0]).cross(f);
      for (int a = 0; a < 3; ++a) {
        force_[a] -= t[a];
        force_[3 + a] -= f[a];
      }
    }
  }
  solve(force_.data(), qdd);
}

}  // namespace physics
}  // namespace car_sim
