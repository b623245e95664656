// The paper's Figure 12 from ../shared/data: poship as an isosurface inside neghip as a
// cloud (see parcMultiVolumeScene.h). The data folder is the first argument; the test is
// only registered when the data are there.
#include "parcMultiVolumeScene.h"

int TestPARCMultiVolumeIronProtein(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestPARCMultiVolumeIronProtein <data folder> [regression options]\n";
    return EXIT_FAILURE;
  }
  return parctest::RunMultiVolumeTest(parctest::IronProtein(argv[1]), argc, argv);
}
