// Cell scalars (vtkVolumeMapper::SetScalarModeToUseCellData): the wavelet's point values
// averaged onto its 63^3 cells by vtkPointDataToCellData, rendered as VTK's GPU mapper
// renders cell data, as voxels at the cell centres. Compared with vtkGPUVolumeRayCastMapper.
#include "parcExampleHarness.h"

#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkPointDataToCellData.h>

int main(int argc, char* argv[])
{
  const auto scene = [](vtkRenderer* renderer, auto* mapper) {
    vtkNew<vtkPointDataToCellData> cells;
    cells->SetInputData(parcexample::MakeWavelet());
    cells->PassPointDataOff();
    mapper->SetInputConnection(cells->GetOutputPort());
    mapper->SetScalarModeToUseCellData();
    parcexample::SampleAlike(mapper);
    parcexample::AddVolume(renderer, mapper, parcexample::MakeWaveletProperty());
  };
  return parcexample::CompareWithVTK<vtkGPUVolumeRayCastMapper>(
    argc, argv, "CellScalars", scene, parcexample::AgainstGPU);
}
