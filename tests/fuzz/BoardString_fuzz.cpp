// libFuzzer target: the calibration board string (`calibrate --board`, `view --calibrate`).
#include "FuzzInput.hpp"
#include "engine/calibration/CalibrationBoard.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  reftrack::fuzz::expectOnlyReftrackErrors([&] {
    const reftrack::CalibrationBoard board =
        reftrack::CalibrationBoard::parse(reftrack::fuzz::text(data, size));
    // A parsed board is usable: its grid and corner positions are defined.
    const cv::Size grid = board.cornerGrid();
    if (grid.area() > 0) (void)board.cornerPosition(grid.area() - 1);
    (void)reftrack::CalibrationBoard::parse(board.toString());
  });
  return 0;
}
