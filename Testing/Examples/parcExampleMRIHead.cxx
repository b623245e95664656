// Real data as a medical user opens it: the MNI ch2 MRI head (Debian's mricron-data,
// 181x217x181 voxels of 1 mm) read with vtkNIFTIImageReader, rendered as a translucent
// head (composite) and as a maximum intensity projection. Compared with
// vtkFixedPointVolumeRayCastMapper. Skipped when the file is absent.
#include "parcExampleHarness.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkNIFTIImageReader.h>

#include <fstream>

namespace
{
constexpr const char* HeadFile = "/usr/share/mricron/templates/ch2.nii.gz";

auto HeadScene(vtkImageData* head, int blendMode)
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    mapper->SetInputData(head);
    mapper->SetBlendMode(blendMode);
    parcexample::SampleAlike(mapper);
    double range[2];
    head->GetScalarRange(range);
    const double width = range[1] - range[0];
    vtkNew<vtkPiecewiseFunction> opacity; // skin faint, brain denser
    opacity->AddPoint(range[0], 0.0);
    opacity->AddPoint(range[0] + 0.15 * width, 0.0);
    opacity->AddPoint(range[0] + 0.35 * width, 0.04);
    opacity->AddPoint(range[0] + 0.6 * width, 0.12);
    opacity->AddPoint(range[1], 0.5);
    vtkNew<vtkColorTransferFunction> color;
    color->AddRGBPoint(range[0], 0.0, 0.0, 0.0);
    color->AddRGBPoint(range[0] + 0.15 * width, 0.55, 0.25, 0.15);
    color->AddRGBPoint(range[0] + 0.6 * width, 0.95, 0.85, 0.75);
    color->AddRGBPoint(range[1], 1.0, 1.0, 0.95);
    vtkNew<vtkVolumeProperty> property;
    property->SetScalarOpacity(opacity);
    property->SetColor(color);
    property->SetInterpolationTypeToLinear();
    parcexample::AddVolume(renderer, mapper, property);
  };
}
}

int main(int argc, char* argv[])
{
  if (!std::ifstream(HeadFile))
  {
    std::cout << HeadFile << " not found (Debian package mricron-data): skipped\n";
    return parcexample::SkipCode;
  }
  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(HeadFile);
  reader->Update();
  vtkImageData* head = reader->GetOutput();
  using parcexample::AgainstFixedPoint;
  using FixedPoint = vtkFixedPointVolumeRayCastMapper;
  return parcexample::CompareWithVTK<FixedPoint>(argc, argv, "MRIHeadComposite",
           HeadScene(head, vtkVolumeMapper::COMPOSITE_BLEND), AgainstFixedPoint) |
    parcexample::CompareWithVTK<FixedPoint>(argc, argv, "MRIHeadMIP",
      HeadScene(head, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND), AgainstFixedPoint);
}
