// Several volumes in one image with the analytic pair (always available): see
// parcMultiVolumeScene.h.
#include "parcMultiVolumeScene.h"

int TestPARCMultiVolume(int argc, char* argv[])
{
  return parctest::RunMultiVolumeTest(parctest::AnalyticPair(), argc, argv);
}
