#include "engine/homography/AnnotationSet.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(AnnotationSet, SaveLoadAndMap) {
  const auto dir = test::freshTempDir("AnnotationSet_roundtrip");
  const AnnotationSet in({{"Tower", {120.5, 80}}, {"Bridge: east end", {10, 200.25}}});
  in.save(dir / "labels.yml");
  const AnnotationSet out = AnnotationSet::load(dir / "labels.yml");
  ASSERT_EQ(out.labels().size(), 2u);
  EXPECT_EQ(out.labels()[1].text, "Bridge: east end");
  EXPECT_DOUBLE_EQ(out.labels()[0].position.x, 120.5);
  const auto m = out.mapped(cv::Matx33d(2, 0, 5, 0, 2, -3, 0, 0, 1));
  EXPECT_DOUBLE_EQ(m[0].x, 246.0);
  EXPECT_DOUBLE_EQ(m[0].y, 157.0);
  const auto inf = out.mapped(cv::Matx33d(1, 0, 0, 0, 1, 0, 0, 0, 0));
  EXPECT_TRUE(std::isnan(inf[0].x));
}

TEST(AnnotationSet, ErrorsNameFileAndEntry) {
  const auto dir = test::freshTempDir("AnnotationSet_errors");
  const auto bad = [&](const std::string& name, const std::string& body) {
    std::ofstream(dir / name) << "%YAML:1.0\n" << body;
    try {
      AnnotationSet::load(dir / name);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(bad("a.yml", "").find("missing key 'labels'"), std::string::npos);
  EXPECT_NE(bad("b.yml", "labels:\n  - { x: 1, y: 2 }\n").find("labels[0]: 'text'"),
            std::string::npos);
  EXPECT_NE(bad("c.yml", "labels:\n  - { text: a, x: 1, y: 2 }\n  - { text: b, x: q, y: 2 }\n")
                .find("labels[1]: 'x'"),
            std::string::npos);
  EXPECT_NE(bad("d.yml", "labels:\n  - { text: a, x: .nan, y: 2 }\n").find("finite"),
            std::string::npos);
  EXPECT_NE(bad("e.yml", "labels: 3\n").find("e.yml"), std::string::npos);
  EXPECT_THROW(AnnotationSet::load(dir / "absent.yml"), Error);
}

TEST(AnnotationSet, LoadsAHandWrittenFileWithoutTheYamlDirective) {
  const auto dir = test::freshTempDir("annotation_no_directive");
  const auto file = dir / "labels.yml";
  {
    std::ofstream out(file);
    out << "labels:\n  - { text: \"Tower\", x: 160.5, y: 80.0 }\n  - { text: \"Desk\", x: 100, "
           "y: 200 }\n";
  }
  const AnnotationSet set = AnnotationSet::load(file);
  ASSERT_EQ(set.labels().size(), 2u);
  EXPECT_EQ(set.labels()[0].text, "Tower");
  EXPECT_DOUBLE_EQ(set.labels()[0].position.x, 160.5);
  EXPECT_DOUBLE_EQ(set.labels()[1].position.y, 200.0);
}

TEST(AnnotationSet, UnknownKeysNameTheNearestKnownKey) {
  const auto dir = test::freshTempDir("AnnotationSet_strict");
  const auto message = [&](const std::string& body) {
    std::ofstream(dir / "l.yml") << body;
    try {
      AnnotationSet::load(dir / "l.yml");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message("lables:\n  - { text: a, x: 1, y: 2 }\n")
                .find("l.yml': line 1: lables: unknown key — did you mean labels?"),
            std::string::npos);
  EXPECT_NE(message("labels:\n  - { text: a, x: 1, y: 2 }\n  - { txt: b, x: 1, y: 2 }\n")
                .find("line 3: labels[1].txt: unknown key — did you mean labels[1].text?"),
            std::string::npos);
  EXPECT_NE(message("labels:\n  - { text: a, x: 1, y: 2, style: { size: 3 } }\n")
                .find("labels[0].style: unknown section"),
            std::string::npos);
}
