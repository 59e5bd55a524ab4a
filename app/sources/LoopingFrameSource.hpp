#pragma once
// LoopingFrameSource: plays a finite, seekable source `loops` times in a row (`view --loop N`,
// used by the soak benchmark). Frame indices and timestamps keep increasing across the seams, so
// the jump back to the first frame looks to the tracker like a sudden camera move.
#include <memory>

#include "app/sources/FrameSource.hpp"

namespace reftrack::app {

class LoopingFrameSource final : public FrameSource {
 public:
  // Throws reftrack::Error when loops < 1 or the source is live, not seekable or empty.
  LoopingFrameSource(std::unique_ptr<FrameSource> inner, int loops);

  std::optional<Frame> next() override;
  std::optional<int> frameCount() const override { return count_ * loops_; }
  double fps() const override { return inner_->fps(); }
  bool seekable() const override { return true; }
  void seek(int index) override;
  std::string description() const override;

 private:
  std::unique_ptr<FrameSource> inner_;
  int loops_, count_;
  int loop_ = 0;  // the pass the next frame belongs to
};

}  // namespace reftrack::app
