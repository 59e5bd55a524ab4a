// ConfigFile: user-written YAML is read with or without its %YAML:1.0 line, after the subset check
// (YamlSubsetValidator); XML and JSON are refused with a clear message.
#include "engine/config/ConfigFile.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <future>
#include <iostream>

#include "TestPaths.hpp"
#include "engine/config/ParamsTestSupport.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/estimation/MotionModelFile.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/homography/AnnotationSet.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/reference/ReferencePreparer.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(ConfigFile, AddsTheYamlDirectiveOnlyWhereOpenCvNeedsIt) {
  EXPECT_EQ(withYamlDirective("a: 1\n"), "%YAML:1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("# comment\na: 1\n"), "%YAML:1.0\n# comment\na: 1\n");
  EXPECT_EQ(withYamlDirective("---\na: 1\n"), "%YAML:1.0\n---\na: 1\n");
  EXPECT_EQ(withYamlDirective(""), "%YAML:1.0\n");
  EXPECT_EQ(withYamlDirective("%YAML:1.0\na: 1\n"), "%YAML:1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("%YAML 1.0\na: 1\n"), "%YAML 1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("\xEF\xBB\xBF%YAML:1.0\na: 1\n"), "%YAML:1.0\na: 1\n");
  EXPECT_EQ(withYamlDirective("\xEF\xBB\xBF"
                              "a: 1\n"),
            "%YAML:1.0\na: 1\n");
}

TEST(ConfigFile, ReadsYamlWithAndWithoutTheDirective) {
  for (const std::string text :
       {"ransac:\n  max_iterations: 7\n", "%YAML:1.0\nransac:\n  max_iterations: 7\n",
        "%YAML:1.0\n---\nransac: {max_iterations: 7}\n", "# mine\nransac: {max_iterations: 7}\n",
        "\xEF\xBB\xBFransac:\r\n  max_iterations: 7\r\n"}) {
    const cv::FileStorage fs = openConfigText(text, "test file");
    EXPECT_EQ(static_cast<int>(fs["ransac"]["max_iterations"]), 7) << text;
  }
}

TEST(ConfigFile, XmlAndJsonAreRefusedWithWhatToWriteInstead) {
  EXPECT_EQ(errorMessage([&] {
              openConfigText("<?xml version=\"1.0\"?>\n<opencv_storage><a>7</a></opencv_storage>\n",
                             "file 'p.xml'");
            }),
            "file 'p.xml' is not valid YAML: line 1: this looks like XML; reftrack reads YAML "
            "only ('key: value' lines)");
  EXPECT_EQ(errorMessage([&] { openConfigText("{\"ransac\": {\"max_iterations\": 7}}", "f"); }),
            "f is not valid YAML: line 1: a top-level { } map (or JSON) is not supported: write "
            "'key: value' lines starting at column 1");
}

TEST(ConfigFile, FailuresNameTheFile) {
  const auto dir = freshTempDir("ConfigFile_failures");
  std::ofstream(dir / "bad.yml") << "ransac: [unclosed\n";
  const std::string parse =
      errorMessage([&] { openConfigFile(dir / "bad.yml", "file 'bad.yml'"); });
  EXPECT_EQ(parse, "file 'bad.yml' is not valid YAML: line 1: '[' is never closed with ']'");
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
  EXPECT_EQ(tag.rfind("f is not valid YAML: line 3: ", 0), 0u) << tag;
  // A top-level list or value: OpenCV asserts (cv::Exception) when a key is looked up in it.
  for (const std::string text : {"- 1\n- 2\n", "%YAML:1.0\n---\n!labels:\n  - 1\n", "3\n"}) {
    const std::string message = errorMessage([&] { openConfigText(text, "f"); });
    EXPECT_TRUE(message == "f must hold a map of key: value at the top level" ||
                message.rfind("f is not valid YAML", 0) == 0)
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
    EXPECT_NE(message.find("f is not valid YAML: line "), std::string::npos) << message;
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

// Every input the fuzzers found OpenCV 4.6's parser hanging on (tests/fuzz/regressions/yaml; each
// still hangs cv::FileStorage directly) is refused by every YAML reader with a line-numbered
// message, in well under the watchdog's time. A reader that hung would end the run here.
TEST(ConfigFile, FuzzFindingsAreRefusedByEveryReaderWithoutHanging) {
  const auto regressions = test::sourceDir() / "tests" / "fuzz" / "regressions" / "yaml";
  const auto dir = freshTempDir("ConfigFile_fuzz_findings");
  std::filesystem::create_directories(dir / "map");
  const std::vector<std::pair<std::string, std::function<void(const std::filesystem::path&)>>>
      readers = {
          {"camera", [](const auto& f) { PinholeCamera::load(f); }},
          {"labels", [](const auto& f) { AnnotationSet::load(f); }},
          {"motion", [](const auto& f) { loadMotionModel(f); }},
          {"tracker parameters", [](const auto& f) { TrackerParams::load(f); }},
          {"preparation parameters", [](const auto& f) { ReferencePreparerParams::load(f); }},
          {"map",
           [&](const auto& f) {
             std::filesystem::copy_file(f, dir / "map" / "map.yml",
                                        std::filesystem::copy_options::overwrite_existing);
             MultiReferenceMap::load(dir / "map");
           }},
      };
  int replayed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(regressions)) {
    for (const auto& [name, read] : readers) {
      auto result = std::async(std::launch::async, [&, read = read] {
        return errorMessage([&] { read(entry.path()); });
      });
      // Each takes well under a millisecond; 30 s leaves room for a loaded, sanitized build.
      if (result.wait_for(std::chrono::seconds(30)) != std::future_status::ready) {
        std::cerr << name << " reader hangs on " << entry.path() << "\n";
        std::_Exit(1);  // the hung thread cannot be joined
      }
      const std::string message = result.get();
      EXPECT_NE(message.find("line "), std::string::npos)
          << name << " on " << entry.path() << ": " << message;
      ++replayed;
    }
  }
  EXPECT_GE(replayed, 5 * static_cast<int>(readers.size()));
}
