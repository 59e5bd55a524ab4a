#include "engine/estimation/MotionModel.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(ArMotionModel, DefaultPredictsThePreviousState) {
  const ArMotionModel m;
  EXPECT_EQ(m.order(), 1);
  const Vector6d x = (Vector6d() << 1, 2, 3, 0.1, 0.2, 0.3).finished();
  EXPECT_EQ(m.predict({x}), x);
}

TEST(ArMotionModel, SecondOrderCombinesLags) {
  const Vector6d w1 = Vector6d::Constant(1.6), w2 = Vector6d::Constant(-0.64);
  const ArMotionModel m({w1, w2}, ArMotionModel::diagonalNoise(0.001, 0.002));
  const Vector6d a = Vector6d::Constant(2.0), b = Vector6d::Constant(1.0);
  EXPECT_TRUE(m.predict({a, b}).isApprox(Vector6d::Constant(1.6 * 2 - 0.64)));
  // Short history: the missing lag repeats the oldest state.
  EXPECT_TRUE(m.predict({a}).isApprox(Vector6d::Constant((1.6 - 0.64) * 2)));
}

TEST(ArMotionModel, RejectsBadNoiseAndWeights) {
  Matrix6d Q = ArMotionModel::diagonalNoise(0.001, 0.001);
  Q(0, 0) = -1;
  EXPECT_THROW(ArMotionModel({Vector6d::Ones()}, Q), Error);
  Vector6d w = Vector6d::Ones();
  w[2] = NAN;
  EXPECT_THROW(ArMotionModel({w}, ArMotionModel::diagonalNoise(0.001, 0.001)), Error);
  EXPECT_THROW(ArMotionModel({}, ArMotionModel::diagonalNoise(0.001, 0.001)), Error);
}

// NaN or infinity in the weights or in Q is refused with the entry at fault named.
TEST(ArMotionModel, NonFiniteEntriesAreNamed) {
  auto message = [](const std::vector<Vector6d>& weights, const Matrix6d& Q) -> std::string {
    try {
      ArMotionModel(weights, Q);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  const Matrix6d Q = ArMotionModel::diagonalNoise(0.001, 0.001);
  Vector6d w = Vector6d::Ones();
  w[4] = INFINITY;
  EXPECT_NE(message({Vector6d::Ones(), w}, Q).find("lag 2"), std::string::npos);
  Matrix6d nanQ = Q;
  nanQ(3, 3) = NAN;
  EXPECT_NE(message({Vector6d::Ones()}, nanQ).find("Q"), std::string::npos);
  Matrix6d infQ = Q;
  infQ(0, 1) = infQ(1, 0) = INFINITY;
  EXPECT_NE(message({Vector6d::Ones()}, infQ).find("Q"), std::string::npos);
}
