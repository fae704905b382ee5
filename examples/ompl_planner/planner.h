// SPDX-License-Identifier: BSD-3-Clause
// The pieces an OMPL planner needs to plan a rigid cylinder through a
// triangle mesh with tricyl (issue 22): the environment as FCL holds it, a
// StateValidityChecker that calls tricyl::collide (directly, or through
// FCL's broadphase), and a MotionValidator whose resolution is a distance
// in the world: no point of the robot moves more than `step` between two
// checked states. Copy this file; docs/planners.md explains each choice.
//
// Why the robot is checked grown by step / 2 (radius + step / 2, length +
// step): OMPL validates a motion at discrete states only. If no point of
// the robot moves more than `step` (along its path) between two checked
// states, every point of the robot at an instant in between is within
// step / 2 of where the same point was at one of them, so the robot at that
// instant lies inside the union of the grown cylinders at the two checked
// states. Checking the grown cylinder at the discrete states therefore
// proves the whole motion free, not just the states (with an exact narrow
// phase: tricyl).
#pragma once

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/narrowphase/collision.h>
#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>
#include <ompl/base/spaces/SE3StateSpace.h>
#include <tricyl/fcl_solver.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "example_mesh.h"

namespace example {

namespace ob = ompl::base;

/// The pose of the robot in an SE(3) state: OMPL's unit quaternion as a
/// rotation matrix (a proper rotation, det R = +1 up to rounding).
inline fcl::Transform3d toTransform(const ob::State* state) {
  const auto* s = state->as<ob::SE3StateSpace::StateType>();
  const auto& q = s->rotation();
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
  tf.translation() = fcl::Vector3d(s->getX(), s->getY(), s->getZ());
  return tf;
}

/// The environment: the whole mesh as one BVH (the direct path) and the same
/// triangles as one collision object per connected part in FCL's dynamic
/// AABB tree (the broadphase path, as a planning scene holds its bodies).
struct Environment {
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> mesh;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> parts;
  fcl::DynamicAABBTreeCollisionManagerd manager;

  explicit Environment(const Mesh& m) : mesh(toBVH(m)) {
    for (const Mesh& part : connectedParts(m)) {
      parts.push_back(std::make_unique<fcl::CollisionObjectd>(
          toBVH(part), fcl::Transform3d::Identity()));
      manager.registerObject(parts.back().get());
    }
    manager.setup();
  }
};

/// Which narrow phase and which path a check takes.
enum class NarrowPhase { kTricyl, kStockFcl };
enum class CheckPath { kDirect, kBroadphase };

/// A state is valid when the robot (the grown cylinder) touches nothing.
/// isValid is const and keeps no state between calls, so the checker can be
/// shared by planner threads.
class CylinderValidityChecker : public ob::StateValidityChecker {
 public:
  CylinderValidityChecker(const ob::SpaceInformationPtr& si,
                          std::shared_ptr<fcl::Cylinderd> robot,
                          const Environment& env, CheckPath path,
                          NarrowPhase narrow = NarrowPhase::kTricyl,
                          fcl::CollisionRequestd request = {})
      : ob::StateValidityChecker(si),
        robot_(std::move(robot)),
        env_(env),
        path_(path),
        narrow_(narrow),
        request_(request) {}

  bool isValid(const ob::State* state) const override {
    return !collides(toTransform(state));
  }

  /// Does the robot at pose `tf` touch the environment? The Boolean query:
  /// the default request stops at the first contact.
  bool collides(const fcl::Transform3d& tf) const {
    const bool tricyl = narrow_ == NarrowPhase::kTricyl;
    if (path_ == CheckPath::kDirect) {
      fcl::CollisionResultd result;
      const auto* env = env_.mesh.get();
      const fcl::Transform3d id = fcl::Transform3d::Identity();
      return (tricyl ? tricyl::collide<double>(robot_.get(), tf, env, id,
                                               request_, result)
                     : fcl::collide<double>(robot_.get(), tf, env, id, request_,
                                            result)) > 0;
    }
    // Broadphase: the robot as a collision object (its constructor computes
    // the world AABB) against the tree of environment parts; the callback
    // runs the narrow phase on each pair whose AABBs overlap.
    fcl::CollisionObjectd robot(robot_, tf);
    fcl::DefaultCollisionData<double> data;
    data.request = request_;
    env_.manager.collide(&robot, &data,
                         tricyl ? tricyl::DefaultCollisionFunction<double>
                                : fcl::DefaultCollisionFunction<double>);
    return data.result.isCollision();
  }

 private:
  std::shared_ptr<fcl::Cylinderd> robot_;
  const Environment& env_;
  CheckPath path_;
  NarrowPhase narrow_;
  fcl::CollisionRequestd request_;
};

/// Validates the motion from s1 to s2 (linear in position, slerp in
/// rotation) at n + 1 evenly spaced states, n chosen so that no point of a
/// body within distance `reach` of its centre moves more than `step`
/// between consecutive ones: a point at distance rho moves along a path of
/// length at most |t2 - t1| + rho * theta, theta the angle of the relative
/// rotation. The first state is taken as valid (OMPL's contract).
class CylinderMotionValidator : public ob::MotionValidator {
 public:
  CylinderMotionValidator(const ob::SpaceInformationPtr& si, double reach,
                          double step)
      : ob::MotionValidator(si), reach_(reach), step_(step) {}

  /// Upper bound on the path length of any point of the robot.
  double sweep(const ob::State* s1, const ob::State* s2) const {
    const auto* a = s1->as<ob::SE3StateSpace::StateType>();
    const auto* b = s2->as<ob::SE3StateSpace::StateType>();
    const auto& qa = a->rotation();
    const auto& qb = b->rotation();
    const Eigen::Quaterniond rel =
        Eigen::Quaterniond(qa.w, qa.x, qa.y, qa.z).conjugate() *
        Eigen::Quaterniond(qb.w, qb.x, qb.y, qb.z);
    // theta = 2 atan2(|v|, |w|): well conditioned near 0, and the short way
    // round, as OMPL's slerp goes.
    const double theta = 2 * std::atan2(rel.vec().norm(), std::abs(rel.w()));
    const double dx = b->getX() - a->getX(), dy = b->getY() - a->getY(),
                 dz = b->getZ() - a->getZ();
    return std::sqrt(dx * dx + dy * dy + dz * dz) + reach_ * theta;
  }

  /// The number of steps for the motion (>= 1); the factor 1 + 1e-9 keeps
  /// the bound above the rounding of `sweep`.
  unsigned steps(const ob::State* s1, const ob::State* s2) const {
    const double n = std::ceil(sweep(s1, s2) * (1 + 1e-9) / step_);
    return n < 1 ? 1u : static_cast<unsigned>(n);
  }

  /// The end state first (most motions a tree planner tries end in an
  /// obstacle), then the states in between, in order.
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    bool ok = si_->isValid(s2);
    const unsigned n = steps(s1, s2);
    ob::State* s = si_->allocState();
    for (unsigned j = 1; j < n && ok; ++j) {
      si_->getStateSpace()->interpolate(s1, s2, double(j) / n, s);
      ok = si_->isValid(s);
    }
    si_->freeState(s);
    ++(ok ? valid_ : invalid_);
    return ok;
  }

  /// In order from s1; on failure, lastValid gets the last valid state (when
  /// its pointer is set) and its fraction of the motion.
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& lastValid) const override {
    const unsigned n = steps(s1, s2);
    ob::State* s = si_->allocState();
    bool ok = true;
    unsigned j = 1;
    for (; j <= n && ok; ++j) {  // the end state last
      if (j == n)
        si_->copyState(s, s2);
      else
        si_->getStateSpace()->interpolate(s1, s2, double(j) / n, s);
      ok = si_->isValid(s);
    }
    if (!ok) {
      lastValid.second = double(j - 2) / n;  // state j - 1 failed
      if (lastValid.first != nullptr)
        si_->getStateSpace()->interpolate(s1, s2, lastValid.second,
                                          lastValid.first);
    }
    si_->freeState(s);
    ++(ok ? valid_ : invalid_);
    return ok;
  }

 private:
  double reach_, step_;
};

/// An SE(3) space over the box [lo, hi] whose distance is the sweep bound
/// above (the rotation weighted by `reach` times 2, since OMPL's SO(3)
/// distance is half the rotation angle), so that the planner's range and
/// nearest neighbours are measured in the same world units as `step`.
inline std::shared_ptr<ob::SE3StateSpace> makeSpace(const fcl::Vector3d& lo,
                                                    const fcl::Vector3d& hi,
                                                    double reach) {
  auto space = std::make_shared<ob::SE3StateSpace>();
  ob::RealVectorBounds bounds(3);
  for (int i = 0; i < 3; ++i) {
    bounds.setLow(i, lo[i]);
    bounds.setHigh(i, hi[i]);
  }
  space->setBounds(bounds);
  space->setSubspaceWeight(1, 2 * reach);
  return space;
}

/// Sets an SE(3) state: position and the rotation taking +z (the cylinder's
/// axis) to `axis`, turned by `spin` about it.
inline void setState(ob::State* state, const fcl::Vector3d& p,
                     const fcl::Vector3d& axis, double spin = 0) {
  auto* s = state->as<ob::SE3StateSpace::StateType>();
  s->setXYZ(p.x(), p.y(), p.z());
  const Eigen::Quaterniond q =
      Eigen::Quaterniond::FromTwoVectors(fcl::Vector3d::UnitZ(),
                                         axis.normalized()) *
      Eigen::Quaterniond(Eigen::AngleAxisd(spin, fcl::Vector3d::UnitZ()));
  auto& r = s->rotation();
  r.x = q.x();
  r.y = q.y();
  r.z = q.z();
  r.w = q.w();
}

}  // namespace example
