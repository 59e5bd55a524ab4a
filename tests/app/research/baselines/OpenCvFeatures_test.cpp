#include "app/research/baselines/OpenCvFeatures.hpp"

#include <gtest/gtest.h>

#include "ErrorMessage.hpp"

namespace reftrack::app {
namespace {

// Each name gives its detector and the norm its descriptors need (L2 for SIFT's floats, Hamming
// for the binary AKAZE and ORB), and ORB its feature budget.
TEST(OpenCvFeatures, NamesGiveTheDetectorAndItsNorm) {
  const OpenCvFeatures sift = openCvFeatures("sift");
  ASSERT_TRUE(sift.detector);
  EXPECT_EQ(sift.norm, cv::NORM_L2);
  EXPECT_EQ(sift.detector->descriptorType(), CV_32F);
  const OpenCvFeatures akaze = openCvFeatures("akaze");
  EXPECT_EQ(akaze.norm, cv::NORM_HAMMING);
  EXPECT_EQ(akaze.detector->descriptorType(), CV_8U);
  const OpenCvFeatures orb = openCvFeatures("orb", 1234);
  EXPECT_EQ(orb.norm, cv::NORM_HAMMING);
  const auto* orbDetector = dynamic_cast<const cv::ORB*>(orb.detector.get());
  ASSERT_NE(orbDetector, nullptr);
  EXPECT_EQ(orbDetector->getMaxFeatures(), 1234);
  const std::string m = test::errorMessage([] { openCvFeatures("SIFT"); });
  EXPECT_NE(m.find("'sift', 'akaze' or 'orb', got 'SIFT'"), std::string::npos) << m;
}

}  // namespace
}  // namespace reftrack::app
