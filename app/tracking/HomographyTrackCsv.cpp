#include "app/tracking/HomographyTrackCsv.hpp"

#include <cstdio>
#include <fstream>

#include "engine/core/AtomicFile.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

// A CSV field: quoted, inner quotes doubled (reasons hold commas).
std::string quoted(const std::string& text) {
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::string homographyCsvHeader() {
  return "index,timestamp,status,inlier_ratio,h11,h12,h13,h21,h22,h23,h31,h32,h33,ms,reason";
}

std::string homographyCsvRow(const HomographyFrameRecord& r) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, ",%.6f", r.timestamp);
  std::string row = std::to_string(r.index) + buffer + (r.tracked ? ",tracked" : ",lost");
  std::snprintf(buffer, sizeof buffer, ",%.4f", r.inlierRatio);
  row += buffer;
  for (int k = 0; k < 9; ++k) {
    // %.10g keeps the projective terms (~1e-4) and the translations (~1e2) exact to ~1e-10.
    std::snprintf(buffer, sizeof buffer, ",%.10g", r.H.val[k]);
    row += buffer;
  }
  std::snprintf(buffer, sizeof buffer, ",%.3f,", r.milliseconds);
  return row + buffer + quoted(r.tracked ? "" : r.reason);
}

void writeHomographyCsv(const std::filesystem::path& file,
                        const std::vector<HomographyFrameRecord>& records) {
  writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    if (!out) throw Error("cannot write CSV '" + file.string() + "'");
    out << homographyCsvHeader() << '\n';
    for (const HomographyFrameRecord& r : records) out << homographyCsvRow(r) << '\n';
    out.flush();
    if (!out) throw Error("write failed for CSV '" + file.string() + "'");
  });
}

}  // namespace reftrack::app
