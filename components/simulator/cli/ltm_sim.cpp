// ltm_sim: writes one session of a simulated scenario as a KITTI-layout folder.
#include "simulator/cli/sim_run.hpp"

int main(int argc, char** argv) { return ltm::sim::cli::sim_main(argc, argv); }
