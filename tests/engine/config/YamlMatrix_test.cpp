// YamlMatrix: OpenCV's matrices as cv::FileStorage writes them, read back exactly; a header that
// disagrees with its data is refused before anything is allocated.
#include "engine/config/YamlMatrix.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

namespace {

std::string matrixError(const std::string& rows, const std::string& cols, const std::string& dt,
                        const std::string& data) {
  const YamlNode root =
      parseYaml("cam:\n  K: !!opencv-matrix\n    rows: " + rows + "\n    cols: " + cols +
                "\n    dt: " + dt + "\n    data: [" + data + "]\n");
  return errorMessage([&] { readYamlMatrix(root["cam"]["K"]); });
}

}  // namespace

TEST(YamlMatrix, ReadsWhatFileStorageWritesExactly) {
  cv::Mat d(3, 4, CV_64F), f(2, 3, CV_32FC3), u(5, 32, CV_8U), s(2, 2, CV_16S), i(1, 3, CV_32S);
  cv::randn(d, 0, 1e3);
  cv::randn(f, 0, 1);
  cv::randu(u, 0, 256);
  cv::randu(s, -32768, 32767);
  i = (cv::Mat_<int>(1, 3) << -2147483647 - 1, 0, 2147483647);
  d.at<double>(0, 1) = NAN;
  d.at<double>(1, 1) = -INFINITY;
  cv::FileStorage out(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  out << "d" << d << "f" << f << "u" << u << "s" << s << "i" << i << "empty" << cv::Mat() << "none"
      << cv::Mat(0, 3, CV_32F);
  const YamlNode root = parseYaml(out.releaseAndGetString());
  cv::Mat dBack = readYamlMatrix(root["d"]);
  EXPECT_TRUE(std::isnan(dBack.at<double>(0, 1)));
  d.at<double>(0, 1) = dBack.at<double>(0, 1) = 0;
  EXPECT_EQ(cv::norm(dBack, d, cv::NORM_INF), 0.0);  // 17 digits: exact, infinities too
  for (const auto& [key, m] : {std::pair{"f", f}, {"u", u}, {"s", s}, {"i", i}}) {
    const cv::Mat back = readYamlMatrix(root[key]);
    EXPECT_EQ(back.type(), m.type()) << key;
    EXPECT_EQ(cv::norm(back, m, cv::NORM_INF), 0.0) << key;
  }
  EXPECT_TRUE(readYamlMatrix(root["empty"]).empty());
  EXPECT_EQ(readYamlMatrix(root["none"]).size(), cv::Size(3, 0));
}

TEST(YamlMatrix, AcceptsAHandWrittenMatrixWithoutTheTag) {
  const cv::Mat m =
      readYamlMatrix(parseYaml("K: {rows: 2, cols: 2, dt: d, data: [1, 2, 3, 4]}\n")["K"]);
  EXPECT_EQ(m.at<double>(1, 0), 3.0);
}

TEST(YamlMatrix, AHeaderThatDisagreesWithItsDataIsRefusedWithItsLine) {
  EXPECT_EQ(matrixError("2", "2", "d", "1, 2, 3, 4"), "(no error)");
  EXPECT_EQ(matrixError("1", "2", "\"3f\"", "1, 2, 3, 4, 5, 6"), "(no error)");
  EXPECT_EQ(matrixError("0", "3", "f", ""), "(no error)");
  // cv::FileStorage would first allocate 10^10 doubles (80 GB) for this file of a hundred bytes.
  EXPECT_EQ(matrixError("100000", "100000", "d", "1"),
            "line 2: cam.K is not a valid matrix: it is too large");
  EXPECT_EQ(matrixError("10000", "10000", "d", "1"),
            "line 6: cam.K is not a valid matrix: its header asks for 100000000 values but 'data' "
            "holds 1");
  EXPECT_EQ(matrixError("2000000000", "2000000000", "d", "1"),
            "line 2: cam.K is not a valid matrix: it is too large");
  EXPECT_EQ(matrixError("-1", "2", "d", "1, 2"),
            "line 3: cam.K is not a valid matrix: 'rows' must be a count");
  EXPECT_EQ(matrixError("1", "1", "dd", "1"),
            "line 5: cam.K is not a valid matrix: 'dt' must be an element type such as d or 3f");
  EXPECT_EQ(matrixError("1", "1", "\"999d\"", "1"),
            "line 5: cam.K is not a valid matrix: 'dt' must be an element type such as d or 3f");
  EXPECT_EQ(matrixError("1", "2", "u", "1, 256"),
            "line 6: cam.K is not a valid matrix: 'data' holds 256, which dt 'u' cannot hold");
  EXPECT_EQ(matrixError("1", "2", "i", "1, 2.5"),
            "line 6: cam.K is not a valid matrix: 'data' holds 2.5, which dt 'i' cannot hold");
  EXPECT_EQ(matrixError("1", "2", "d", "1, x"),
            "line 6: cam.K is not a valid matrix: 'data' must hold numbers only");
  EXPECT_EQ(errorMessage([&] {
              readYamlMatrix(parseYaml("K: {rows: 1, cols: 1, dt: d, dat: [1]}\n")["K"]);
            }),
            "line 1: K.dat: unknown key — did you mean K.data?");
  EXPECT_EQ(errorMessage([&] { readYamlMatrix(parseYaml("K: [1, 2]\n")["K"]); }),
            "line 1: K is not a valid matrix: it must be a map of rows, cols, dt and data "
            "(!!opencv-matrix)");
  EXPECT_EQ(errorMessage([&] { readYamlMatrix(parseYaml("a: 1\n")["K"]); }),
            "line 1: K is missing");
  // Inside lists too, named by position.
  EXPECT_NE(errorMessage([&] {
              readYamlMatrix(parseYaml("views:\n  - { name: a }\n  - { T: !!opencv-matrix { rows: "
                                       "4, cols: 4, dt: d, data: [1] } }\n")["views"]
                                 .item(1)["T"]);
            }).find("views[1].T is not a valid matrix"),
            std::string::npos);
}
