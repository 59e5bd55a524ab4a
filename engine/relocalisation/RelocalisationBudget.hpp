#pragma once
// RelocalisationBudget: when a lost tracker may try to relocalise. A bucket of milliseconds:
// full (burstMs) while tracking, refilled by msPerFrame per lost frame (up to burstMs), emptied
// by what each attempt cost; an attempt is due while it holds anything. So attempts come on
// every frame at first and then back off, spending at most burstMs + msPerFrame per lost frame.
// With a reserve, an attempt on any frame is due only while the bucket holds more than the
// reserve; the reserve is kept for frames that look like the scene (SceneResemblance), so a
// search is at hand when the scene comes back. The bucket only counts: what an attempt costs is
// the caller's (MultiReferenceTracker charges the modelled cost of the work on recorded input,
// RecoveryWork, or measured CPU time live).
namespace reftrack {

class RelocalisationBudget {
 public:
  // Throws reftrack::Error for a negative or non-finite rate or burst, or a reserve share
  // outside [0, 1) (the share of the burst kept for frames that look like the scene).
  RelocalisationBudget(double msPerFrame, double burstMs, double reserveShare = 0.0);
  // New rates (as the constructor checks them), the bucket full; spentInAll() goes on counting.
  void configure(double msPerFrame, double burstMs, double reserveShare = 0.0);

  void refill();  // tracking again: the whole burst is available
  // One more lost frame: its share is added; true when an attempt is due on any frame (the
  // bucket holds more than the reserve).
  bool lostFrame();
  // An attempt on a frame that looks like the scene is due (the bucket holds anything).
  bool reserveHolds() const { return bucketMs_ > 0.0; }
  void spent(double ms);  // what an attempt cost (ms; negative or NaN counts as 0)

  double available() const { return bucketMs_; }  // may be negative right after an attempt
  double spentInAll() const { return spentMs_; }  // every attempt's cost since construction

 private:
  double msPerFrame_ = 0.0, burstMs_ = 0.0, reserveMs_ = 0.0;
  double bucketMs_ = 0.0;
  double spentMs_ = 0.0;
};

}  // namespace reftrack
