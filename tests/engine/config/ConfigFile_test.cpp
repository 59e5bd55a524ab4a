// ConfigFile: user-written YAML is read with or without its %YAML:1.0 line; XML and JSON as is.
#include "engine/config/ConfigFile.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "TestPaths.hpp"
#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(ConfigFile, AddsTheYamlDirectiveOnlyWhereOpenCvNeedsIt) {
  EXPECT_EQ(withYamlDirective("a: 1\n"), "%YAML:1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("# comment\na: 1\n"), "%YAML:1.0\n# comment\na: 1\n");
  EXPECT_EQ(withYamlDirective("---\na: 1\n"), "%YAML:1.0\n---\na: 1\n");
  EXPECT_EQ(withYamlDirective(""), "%YAML:1.0\n");
  EXPECT_EQ(withYamlDirective("%YAML:1.0\na: 1\n"), "%YAML:1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("%YAML 1.0\na: 1\n"), "%YAML 1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("\xEF\xBB\xBF%YAML:1.0\na: 1\n"), "\xEF\xBB\xBF%YAML:1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("\xEF\xBB\xBF"
                              "a: 1\n"),
            "%YAML:1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("<?xml version=\"1.0\"?>\n<opencv_storage/>\n"),
            "<?xml version=\"1.0\"?>\n<opencv_storage/>\n");
  EXPECT_EQ(withYamlDirective("{\"a\": 1}"), "{\"a\": 1}");
}

TEST(ConfigFile, ReadsYamlWithAndWithoutTheDirectiveXmlAndJson) {
  for (const std::string text :
       {"ransac:\n  max_iterations: 7\n", "%YAML:1.0\nransac:\n  max_iterations: 7\n",
        "%YAML:1.0\n---\nransac: {max_iterations: 7}\n", "# mine\nransac: {max_iterations: 7}\n",
        "{\"ransac\": {\"max_iterations\": 7}}",
        "<?xml version=\"1.0\"?>\n<opencv_storage><ransac><max_iterations>7</max_iterations>"
        "</ransac></opencv_storage>\n"}) {
    const cv::FileStorage fs = openConfigText(text, "test file");
    EXPECT_EQ(static_cast<int>(fs["ransac"]["max_iterations"]), 7) << text;
  }
}

TEST(ConfigFile, FailuresNameTheFile) {
  const auto dir = freshTempDir("ConfigFile_failures");
  std::ofstream(dir / "bad.yml") << "ransac: [unclosed\n";
  const std::string parse =
      errorMessage([&] { openConfigFile(dir / "bad.yml", "file 'bad.yml'"); });
  EXPECT_EQ(parse.rfind("file 'bad.yml' is not valid OpenCV YAML/XML", 0), 0u) << parse;
  EXPECT_EQ(errorMessage([&] {
              openConfigFile(dir / "bad.yml", "map", "is corrupt");
            }).rfind("map is corrupt", 0),
            0u);
  EXPECT_EQ(errorMessage([&] { openConfigFile(dir, "folder"); }), "folder is a folder, not a file");
  EXPECT_EQ(errorMessage([&] { openConfigFile(dir / "absent.yml", "absent"); }),
            "absent cannot be read");
  std::ofstream(dir / "empty.yml").close();
  EXPECT_EQ(errorMessage([&] { openConfigFile(dir / "empty.yml", "empty"); }), "(no error)");
}

TEST(ConfigFile, AMatrixWhoseHeaderDisagreesWithItsDataIsRefusedBeforeOpenCvAllocatesIt) {
  const auto matrix = [](const std::string& rows, const std::string& cols, const std::string& dt,
                         const std::string& data) {
    return "cam:\n  K: !!opencv-matrix\n    rows: " + rows + "\n    cols: " + cols +
           "\n    dt: " + dt + "\n    data: [" + data + "]\n";
  };
  const auto load = [](const std::string& text) {
    return errorMessage([&] { openConfigText(text, "f"); });
  };
  EXPECT_EQ(load(matrix("2", "2", "d", "1, 2, 3, 4")), "(no error)");
  EXPECT_EQ(load(matrix("1", "2", "\"3f\"", "1, 2, 3, 4, 5, 6")), "(no error)");
  EXPECT_EQ(load(matrix("0", "3", "f", "")), "(no error)");
  // OpenCV would first allocate 10^10 doubles (80 GB) for this file of a hundred bytes.
  EXPECT_EQ(load(matrix("100000", "100000", "d", "1")),
            "f: cam.K is not a valid matrix: its header asks for 10000000000 values but 'data' "
            "holds 1");
  EXPECT_EQ(load(matrix("2000000000", "2000000000", "d", "1")),
            "f: cam.K is not a valid matrix: it is too large");
  EXPECT_EQ(load(matrix("-1", "2", "d", "1, 2")),
            "f: cam.K is not a valid matrix: 'rows' must be a count");
  EXPECT_EQ(load(matrix("1", "1", "dd", "1")),
            "f: cam.K is not a valid matrix: 'dt' must be an element type such as d or 3f");
  EXPECT_EQ(load(matrix("1", "1", "\"999d\"", "1")),
            "f: cam.K is not a valid matrix: 'dt' must be an element type such as d or 3f");
  // Inside lists too, named by position.
  EXPECT_NE(load("views:\n  - { name: a }\n  - { T: !!opencv-matrix { rows: 4, cols: 4, dt: d, "
                 "data: [1] } }\n")
                .find("views[1].T is not a valid matrix"),
            std::string::npos);
}

// Regressions found by tests/fuzz (fuzz_camera_file, fuzz_labels_file, fuzz_motion_model_file).
TEST(ConfigFile, ParserFailuresAndANonMapRootAreReftrackErrors) {
  // OpenCV 4.6's parser threw std::length_error (not cv::Exception) on this mangled type tag.
  const std::string mangledTag =
      "image_width: 640\nimage_height: 480\n`amera_matrix: !!opencv-matrix\n   rows: 2\n   cols: "
      "3\n   :td d\n   data: [ 500., 0., 319.5, 0., 500., 239.5, 0., 0., 1. "
      "]\ndistortion_coefficients: "
      "!!opencv-"
      "ma\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc"
      "\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc"
      "\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcctrix\n   rows: 5\n   cols: 1\n   "
      "\x9c\x8b\xc5\xdf\x9b\xf5\xdf\xe6 data: [ 0.1, -0.2, 0., 0., 0. ]\n";
  const std::string tag = errorMessage([&] { openConfigText(mangledTag, "f"); });
  EXPECT_EQ(tag.rfind("f is not valid OpenCV YAML/XML", 0), 0u) << tag;
  // A top-level list or value: OpenCV asserts (cv::Exception) when a key is looked up in it.
  for (const std::string text : {"- 1\n- 2\n", "%YAML:1.0\n---\n!labels:\n  - 1\n", "3\n"}) {
    const std::string message = errorMessage([&] { openConfigText(text, "f"); });
    EXPECT_TRUE(message == "f must hold a map of key: value at the top level" ||
                message.rfind("f is not valid OpenCV YAML/XML", 0) == 0)
        << text << " -> " << message;
  }
}

TEST(ConfigFile, TextsOnWhichOpenCvsParserLoopsAreRefusedFirst) {
  // Found by tests/fuzz: OpenCV 4.6's parser never returned on these (motion and labels).
  const std::string motion = "%YAML:1.0\n---\n# opencv-ix\n   r%YAML:0.0\n--\n-# ";
  const std::string labels = "%YA--\xff labels:\n   -\n      text: To\n";
  const std::string dashes = " -y\nl:\n  -y\n";
  for (const std::string& text : {motion, labels, dashes}) {
    const std::string message = errorMessage([&] { openConfigText(text, "f"); });
    EXPECT_NE(message.find("f is not valid OpenCV YAML/XML: line "), std::string::npos) << message;
  }
  // The directive itself as the first line, '%' inside values (a map stores its preparation
  // parameters as a YAML string), sequences and negative numbers stay fine.
  EXPECT_EQ(errorMessage([&] {
              openConfigText(
                  "%YAML:1.0\n---\ntext: \"%YAML:1.0\\n50% off\"\nlist:\n   - -1\n"
                  "   -\n      x: -2.5\nm: [ -1, 2 ]\n",
                  "f");
            }),
            "(no error)");
}
