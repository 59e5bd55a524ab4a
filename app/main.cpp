// reftrack: marker-less augmented reality camera tracking (Xu, Chia & Cheok 2008).
#include "app/cli/CommandLine.hpp"
#include "app/cli/HeapReuse.hpp"

int main(int argc, char** argv) {
  reftrack::app::keepFreedMemoryForReuse();  // a speed setting: its refusal changes no result
  return reftrack::app::runCommandLine(argc, argv);
}
