// Cell scalars (vtkVolumeMapper::SetScalarModeToUseCellData): the wavelet's point values
// averaged onto its 63^3 cells by vtkPointDataToCellData, rendered as VTK's GPU mapper
// renders cell data, as voxels at the cell centres. Compared with vtkGPUVolumeRayCastMapper.
#include "parcExampleHarness.h"

#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkPointDataToCellData.h>
#include <vtkVolume.h>

int main(int argc, char* argv[])
{
  const auto scene = [](vtkRenderer* renderer, auto* mapper) {
    vtkNew<vtkPointDataToCellData> cells;
    cells->SetInputData(parcexample::MakeWavelet());
    cells->PassPointDataOff();
    mapper->SetInputConnection(cells->GetOutputPort());
    mapper->SetScalarModeToUseCellData();
    mapper->SetAutoAdjustSampleDistances(0);
    mapper->SetLockSampleDistanceToInputSpacing(0);
    mapper->SetSampleDistance(0.5);
    mapper->SetImageSampleDistance(1.0);
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    volume->SetProperty(parcexample::MakeWaveletProperty());
    renderer->AddVolume(volume);
  };
  return parcexample::CompareWithVTK<vtkGPUVolumeRayCastMapper>(
    argc, argv, "CellScalars", scene, parcexample::AgainstGPU);
}
