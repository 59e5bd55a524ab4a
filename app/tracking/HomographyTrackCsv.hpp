#pragma once
// HomographyTrackCsv: the per-frame record of a homography-mode run (`reftrack track --mode
// homography --out-csv`) and its CSV form, one row per frame:
//   index,timestamp,status,inlier_ratio,h11,h12,h13,h21,h22,h23,h31,h32,h33,ms,reason
// timestamp is the frame's (seconds, the dataset's clock for tum:/euroc: inputs); status is
// "tracked" or "lost"; H maps the reference to the frame (identity when lost); reason (quoted,
// inner quotes doubled: it holds commas) says why a lost frame was not registered, and is empty
// for a tracked one.
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace reftrack::app {

struct HomographyFrameRecord {
  int index = 0;
  double timestamp = 0.0;
  bool tracked = false;
  double inlierRatio = 0.0;
  cv::Matx33d H = cv::Matx33d::eye();
  double milliseconds = 0.0;
  std::string reason;  // why the frame is lost (HomographyTrackResult::failure); "" when tracked
};

std::string homographyCsvHeader();  // without the trailing newline
std::string homographyCsvRow(const HomographyFrameRecord& record);

// Writes the header and every row (atomic: temp file + rename). Throws reftrack::Error.
void writeHomographyCsv(const std::filesystem::path& file,
                        const std::vector<HomographyFrameRecord>& records);

}  // namespace reftrack::app
