// reftrack: marker-less augmented reality camera tracking (Xu, Chia & Cheok 2008).
#include "app/cli/CommandLine.hpp"

int main(int argc, char** argv) { return reftrack::app::runCommandLine(argc, argv); }
