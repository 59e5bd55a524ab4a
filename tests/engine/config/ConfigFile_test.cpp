// ConfigFile: a user's YAML file is read by yaml-cpp as YAML 1.2, with or without OpenCV's
// `%YAML:1.0` line; what is not YAML, or not a map at the top, is refused naming the file and line.
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

TEST(ConfigFile, ReadsYamlWithAndWithoutTheDirectiveKeepingLineNumbers) {
  for (const std::string text :
       {"ransac:\n  max_iterations: 7\n", "%YAML:1.0\nransac:\n  max_iterations: 7\n",
        "%YAML:1.0\n---\nransac: {max_iterations: 7}\n",
        "%YAML 1.2\n---\nransac: {max_iterations: 7}\n", "# mine\nransac: {max_iterations: 7}\n",
        "\xEF\xBB\xBFransac:\r\n  max_iterations: 7\r\n",
        "{\"ransac\": {\"max_iterations\": 7}}"}) {
    const YamlNode root = readConfigText(text, "test file");
    EXPECT_EQ(root["ransac"]["max_iterations"].integer(), 7) << text;
  }
  // Lines count from the file's first line, the directive included.
  EXPECT_EQ(readConfigText("%YAML:1.0\n---\na: 1\n", "f")["a"].line(), 3);
  EXPECT_EQ(readConfigText("\xEF\xBB\xBF%YAML:1.0\n\na: 1\n", "f")["a"].line(), 3);
}

TEST(ConfigFile, NotAMapAtTheTopIsRefusedWithWhatToWrite) {
  EXPECT_EQ(errorMessage([&] { readConfigText("- 1\n- 2\n", "f"); }),
            "f must hold a map of key: value at the top level (line 1)");
  EXPECT_EQ(errorMessage([&] { readConfigText("\n3\n", "f"); }),
            "f must hold a map of key: value at the top level (line 2)");
  EXPECT_EQ(errorMessage([&] {
              readConfigText("<?xml version=\"1.0\"?>\n<opencv_storage><a>7</a></opencv_storage>\n",
                             "file 'p.xml'");
            }),
            "file 'p.xml' must hold a map of key: value at the top level (line 1)");
}

TEST(ConfigFile, FailuresNameTheFileAndLine) {
  const auto dir = freshTempDir("ConfigFile_failures");
  std::ofstream(dir / "bad.yml") << "# a list\nransac: [unclosed\n";
  EXPECT_EQ(errorMessage([&] { readConfigFile(dir / "bad.yml", "file 'bad.yml'"); }),
            "file 'bad.yml' is not valid YAML: line 3: end of sequence flow not found");
  EXPECT_EQ(errorMessage([&] {
              readConfigFile(dir / "bad.yml", "map", "is corrupt");
            }).rfind("map is corrupt: line 3", 0),
            0u);
  EXPECT_EQ(errorMessage([&] { readConfigFile(dir, "folder"); }), "folder is a folder, not a file");
  EXPECT_EQ(errorMessage([&] { readConfigFile(dir / "absent.yml", "absent"); }),
            "absent cannot be read");
  std::ofstream(dir / "empty.yml").close();
  EXPECT_TRUE(readConfigFile(dir / "empty.yml", "empty").isNull());
  std::ofstream(dir / "binary.yml", std::ios::binary) << std::string("a: 1\nb: \x01\x02\n", 11);
  EXPECT_EQ(errorMessage([&] { readConfigFile(dir / "binary.yml", "f"); }),
            "f is not valid YAML: line 2: control byte 0x01 (is this a text file?)");
}

// Regressions found by tests/fuzz under OpenCV's parser (fuzz_camera_file, fuzz_labels_file,
// fuzz_motion_model_file), read now by yaml-cpp: refused with a line, or read.
TEST(ConfigFile, OldFuzzFindingsAreRefusedWithALine) {
  const std::string mangledTag =
      "image_width: 640\nimage_height: 480\n`amera_matrix: !!opencv-matrix\n   rows: 2\n   cols: "
      "3\n   :td d\n   data: [ 500., 0., 319.5, 0., 500., 239.5, 0., 0., 1. "
      "]\ndistortion_coefficients: "
      "!!opencv-"
      "ma\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc"
      "\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcc"
      "\xcc\xcc\xcc\xcc\xcc\xcc\xcc\xcctrix\n   rows: 5\n   cols: 1\n   "
      "\x9c\x8b\xc5\xdf\x9b\xf5\xdf\xe6 data: [ 0.1, -0.2, 0., 0., 0. ]\n";
  const std::string motion = "%YAML:1.0\n---\n# opencv-ix\n   r%YAML:0.0\n--\n-# ";
  const std::string labels = "%YA--\xff labels:\n   -\n      text: To\n";
  const std::string dashes = " -y\nl:\n  -y\n";
  for (const std::string& text : {mangledTag, motion, labels, dashes}) {
    const std::string message = errorMessage([&] { readConfigText(text, "f"); });
    EXPECT_TRUE(message.rfind("f is not valid YAML: line ", 0) == 0 ||
                message.rfind("f must hold a map of key: value at the top level (line ", 0) == 0)
        << message;
  }
  // '%' inside values (a map stores its preparation parameters as a YAML string), lists and
  // negative numbers are fine.
  const YamlNode root = readConfigText(
      "%YAML:1.0\n---\ntext: \"%YAML:1.0\\n50% off\"\nlist:\n   - -1\n"
      "   -\n      x: -2.5\nm: [ -1, 2 ]\n",
      "f");
  EXPECT_EQ(root["text"].text(), "%YAML:1.0\n50% off");
  EXPECT_EQ(root["list"].item(1)["x"].number(), -2.5);
}

// Every input the fuzzers found OpenCV 4.6's parser hanging on (tests/fuzz/regressions/yaml) is
// refused by every YAML reader with a line-numbered message, in well under the watchdog's time.
// A reader that hung would end the run here.
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
