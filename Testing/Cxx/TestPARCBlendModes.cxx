// Every blend mode of vtkPARCVolumeMapper on one procedural volume, perspective camera:
// composite shaded, maximum, minimum and average intensity, additive and isosurface.
#include "parcTestScene.h"

#include <vtkRendererCollection.h>
#include <vtkVolumeCollection.h>

#include <iostream>

int TestPARCBlendModes(int argc, char* argv[])
{
  vtkNew<vtkRenderWindow> window;
  window->SetSize(450, 300);
  window->SetMultiSamples(0);
  auto image = parctest::MakeBlobs();
  auto inverted = parctest::MakeBlobs(48, true);
  auto shaded = parctest::MakeProperty(true);
  auto flat = parctest::MakeProperty(false);
  const int modes[6] = { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
    vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND,
    vtkVolumeMapper::ADDITIVE_BLEND, vtkVolumeMapper::ISOSURFACE_BLEND };
  vtkSmartPointer<vtkPARCVolumeMapper> mappers[6];
  for (int m = 0; m < 6; ++m)
  {
    const double vp[4] = { (m % 3) / 3.0, (m / 3) / 2.0, (m % 3 + 1) / 3.0, (m / 3 + 1) / 2.0 };
    const bool shade = modes[m] == vtkVolumeMapper::COMPOSITE_BLEND ||
      modes[m] == vtkVolumeMapper::ISOSURFACE_BLEND;
    const bool minimum = modes[m] == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
    mappers[m] = parctest::AddVolume(
      window, vp, minimum ? inverted : image, shade ? shaded : flat, modes[m]);
  }
  mappers[3]->SetAverageIPScalarRange(30, 255);
  vtkNew<vtkVolumeProperty> minimumProperty; // bright where the inverted volume is low
  minimumProperty->DeepCopy(flat);
  vtkNew<vtkPiecewiseFunction> minimumOpacity;
  minimumOpacity->AddPoint(0, 1.0);
  minimumOpacity->AddPoint(215, 0.0);
  minimumProperty->SetScalarOpacity(minimumOpacity);
  vtkNew<vtkColorTransferFunction> minimumColor;
  minimumColor->AddRGBPoint(0, 1.0, 1.0, 0.9);
  minimumColor->AddRGBPoint(120, 1.0, 0.6, 0.2);
  minimumColor->AddRGBPoint(215, 0.2, 0.4, 1.0);
  minimumProperty->SetColor(minimumColor);
  vtkVolume::SafeDownCast(
    vtkRenderer::SafeDownCast(window->GetRenderers()->GetItemAsObject(2))->GetVolumes()->GetItemAsObject(0))
    ->SetProperty(minimumProperty);
  window->Render();
  for (int m = 0; m < 6; ++m)
  {
    if (mappers[m]->GetLastSampleCount() <= 0 || parctest::MaxAlpha(mappers[m]) <= 0.0)
    {
      std::cerr << "blend mode " << modes[m] << " drew nothing\n";
      return EXIT_FAILURE;
    }
  }
  return parctest::MatchesBaseline(window, argc, argv) ? EXIT_SUCCESS : EXIT_FAILURE;
}
