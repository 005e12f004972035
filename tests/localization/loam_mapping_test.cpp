#include "bipednav/localization/loam_mapping.hpp"

#include <gtest/gtest.h>

#include "bipednav/localization/feature_association.hpp"
#include "bipednav/localization/registration_lm.hpp"

using namespace bipednav;
using namespace bipednav::localization;

namespace {

// The two faces of a wall 0.2 m thick at x = 0 .. 0.2: the near face seen from x = -3, the far
// one from x = +3. Points on a 0.1 m grid in y and z.
struct ThinWall {
  std::vector<Eigen::Vector3f> points, viewpoints;
  ThinWall() {
    for (int face = 0; face < 2; ++face)
      for (int i = -10; i <= 10; ++i)
        for (int j = -10; j <= 10; ++j) {
          points.emplace_back(0.2f * static_cast<float>(face), 0.1f * static_cast<float>(i),
                              0.1f * static_cast<float>(j));
          viewpoints.emplace_back(face == 0 ? -3.0f : 3.0f, 0.0f, 0.0f);
        }
  }
};

}  // namespace

TEST(FeatureAssociation, APatchSeenFromTheOtherSideOfAThinWallIsNotMatched) {
  const ThinWall wall;
  const PointKdTree tree(wall.points);
  AssociationParams p;
  Constraint c;
  // A point of the far face, estimated 0.15 m too far back: its nearest neighbours are on the near face.
  const Eigen::Vector3d q(0.05, 0.0, 0.0);
  ASSERT_TRUE(planar_correspondence(tree, q, 1.0, q, p, c));  // without the check: the wrong face
  EXPECT_NEAR(c.anchor.x(), 0.0, 1e-6);
  const ViewCheck from_far_side{&wall.viewpoints, Eigen::Vector3d(2.0, 0.0, 0.0)};
  EXPECT_FALSE(planar_correspondence(tree, q, 1.0, q, p, c, &from_far_side));
  const Eigen::Vector3d on_far_face(0.17, 0.0, 0.0);
  ASSERT_TRUE(planar_correspondence(tree, on_far_face, 1.0, on_far_face, p, c, &from_far_side));
  EXPECT_NEAR(c.anchor.x(), 0.2, 1e-6);
  const ViewCheck from_near_side{&wall.viewpoints, Eigen::Vector3d(-2.0, 0.0, 0.0)};
  EXPECT_TRUE(planar_correspondence(tree, q, 1.0, q, p, c, &from_near_side));
  const ViewCheck no_viewpoints{};  // a tree without viewpoints is not checked
  EXPECT_TRUE(planar_correspondence(tree, q, 1.0, q, p, c, &no_viewpoints));
}

TEST(FeatureAssociation, HintsGiveTheSameMatches) {
  // Hinted searches (earlier neighbours bound the search, the same neighbours of the same tree
  // reuse their fit) give the constraints of unhinted ones, also when the hint is from another
  // tree or another point.
  const ThinWall wall;
  const PointKdTree tree(wall.points), other(std::vector<Eigen::Vector3f>(wall.points.rbegin(), wall.points.rend()));
  AssociationParams p;
  NeighbourHint hint;
  for (int t = 0; t < 200; ++t) {
    const Eigen::Vector3d q(0.01 * (t % 23) - 0.05, 0.013 * (t % 17) - 0.1, 0.011 * (t % 13) - 0.07);
    const PointKdTree& searched = t % 3 == 0 ? other : tree;
    for (const bool planar : {true, false}) {
      Constraint want, got;
      const bool w = planar ? planar_correspondence(searched, q, 1.0, q, p, want)
                            : edge_correspondence(searched, q, 1.0, q, p, want);
      const bool g = planar ? planar_correspondence(searched, q, 1.0, q, p, got, nullptr, &hint)
                            : edge_correspondence(searched, q, 1.0, q, p, got, nullptr, &hint);
      ASSERT_EQ(g, w) << t;
      if (!w) continue;
      EXPECT_EQ(got.anchor, want.anchor) << t;
      EXPECT_EQ(got.axis, want.axis) << t;
      EXPECT_EQ(got.point, want.point) << t;
    }
  }
}

TEST(FeatureAssociation, AHintsFitIsNotReusedOnceItsTreeIsRebuilt) {
  // The same tree object rebuilt from the wall moved 5 cm along x: the same neighbour indices, so
  // only the tree's generation tells that the hint's fit is of the points before.
  const ThinWall wall;
  PointKdTree tree(wall.points);
  AssociationParams p;
  NeighbourHint hint;
  Constraint before, after, want;
  const Eigen::Vector3d q(-0.02, 0.01, 0.02);
  ASSERT_TRUE(planar_correspondence(tree, q, 1.0, q, p, before, nullptr, &hint));
  std::vector<Eigen::Vector3f> moved = wall.points;
  for (auto& pt : moved) pt.x() += 0.05f;
  tree.build(moved);
  ASSERT_TRUE(planar_correspondence(tree, q, 1.0, q, p, want));
  ASSERT_TRUE(planar_correspondence(tree, q, 1.0, q, p, after, nullptr, &hint));
  EXPECT_NEAR(after.anchor.x(), before.anchor.x() + 0.05, 1e-6);
  EXPECT_EQ(after.anchor, want.anchor);
}

TEST(VoxelPointMap, KeepsBothFacesOfAWallThinnerThanAVoxel) {
  VoxelPointMap map(0.4);
  map.insert({0.05f, 0.1f, 0.1f}, {-3.0f, 0.0f, 0.0f});
  map.insert({0.15f, 0.1f, 0.1f}, {-3.0f, 0.5f, 0.0f});  // same voxel, same side: dropped
  map.insert({0.25f, 0.1f, 0.1f}, {3.0f, 0.0f, 0.0f});   // same voxel, seen from the other side
  ASSERT_EQ(map.size(), 2u);
  EXPECT_FLOAT_EQ(map.viewpoints()[1].x(), 3.0f);
  map.crop({10.0f, 0.0f, 0.0f}, 1.0);
  EXPECT_EQ(map.size(), 0u);
  EXPECT_EQ(map.viewpoints().size(), 0u);
}

TEST(RegistrationLm, HorizontalWeakProjectorKeepsMostlyHorizontalDirections) {
  Matrix6d dirs = Matrix6d::Zero();
  dirs.col(0) << 1, 0, 0, 0, 0, 0;  // x
  dirs.col(1) << 0, 0, 1, 0, 0, 0;  // height
  Eigen::Matrix2d P = horizontal_weak_projector(dirs, 2);
  EXPECT_TRUE(P.isApprox(Eigen::Vector2d(1, 0).asDiagonal().toDenseMatrix()));
  // A direction mostly of yaw (its horizontal part 0.3 long) leaves x and y observed.
  dirs.col(0) << 0.3 / std::sqrt(2.0), 0.3 / std::sqrt(2.0), 0, 0, 0, std::sqrt(1.0 - 0.09);
  EXPECT_TRUE(horizontal_weak_projector(dirs, 1).isZero());
  // x and y both suppressed, in any basis: the identity.
  dirs.col(0) << std::sqrt(0.5), std::sqrt(0.5), 0, 0, 0, 0;
  dirs.col(1) << -std::sqrt(0.5), std::sqrt(0.5), 0, 0, 0, 0;
  EXPECT_TRUE(horizontal_weak_projector(dirs, 2).isApprox(Eigen::Matrix2d::Identity()));
  EXPECT_TRUE(horizontal_weak_projector(dirs, 0).isZero());
}

TEST(RegistrationLm, ALinearPriorFixesADirectionThePointsLeaveFree) {
  // Points on the plane z = 0 observe z, roll and pitch only; a prior pins x to 0.3.
  std::vector<Constraint> cs;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j) {
      Constraint c;
      c.point = Eigen::Vector3d(i, j, 0.1);
      c.anchor = Eigen::Vector3d::Zero();
      c.axis = Eigen::Vector3d::UnitZ();
      cs.push_back(c);
    }
  LmParams p;
  const LmSolution free = solve_lm(cs, Vector6d::Zero(), p);
  EXPECT_NEAR(free.x(2), -0.1, 1e-6);
  EXPECT_NEAR(free.x(0), 0.0, 1e-9);
  EXPECT_EQ(free.degenerate_dims, 3);
  LinearPrior prior;
  prior.A = Eigen::Matrix<double, 1, 6>::Zero();
  prior.A(0, 0) = 1.0;
  prior.b = Eigen::VectorXd::Constant(1, -0.3);
  prior.weight = 100.0;
  const LmSolution pinned = solve_lm(cs, Vector6d::Zero(), p, prior);
  EXPECT_NEAR(pinned.x(0), 0.3, 1e-4);
  EXPECT_NEAR(pinned.x(2), -0.1, 1e-6);
  EXPECT_EQ(pinned.degenerate_dims, 2);
}
