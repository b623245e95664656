// Depth peeling: a volume beside translucent and opaque polydata in a renderer that peels
// (UseDepthPeeling), with and without UseDepthPeelingForVolumes (ParaView's default, where
// VTK's dual depth peeling renders volumes inside its peels through shader code only the GPU
// mapper has). The mapper draws its volume after the peels, over them: the window's pixels
// are the same in both settings, the same in every frame, and the volume shows.
#include "parcTestScene.h"

#include <vtkActor.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRendererCollection.h>
#include <vtkSphereSource.h>
#include <vtkUnsignedCharArray.h>

#include <iostream>
#include <vector>

namespace
{
constexpr int WindowSize = 120;

/// A sphere of the given opacity at centre (world units) in renderer.
void AddSphere(vtkRenderer* renderer, const double centre[3], double radius, double opacity)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(centre[0], centre[1], centre[2]);
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.2, 0.5, 1.0);
  actor->GetProperty()->SetOpacity(opacity);
  renderer->AddActor(actor);
}

/// The window's RGBA pixels after a render.
std::vector<unsigned char> Pixels(vtkRenderWindow* window)
{
  window->Render();
  vtkNew<vtkUnsignedCharArray> rgba;
  window->GetRGBACharPixelData(0, 0, WindowSize - 1, WindowSize - 1, 0, rgba);
  return std::vector<unsigned char>(
    rgba->GetPointer(0), rgba->GetPointer(0) + rgba->GetNumberOfValues());
}
}

int TestPARCDepthPeeling(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = parctest::MakeBlobs(40);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(WindowSize, WindowSize);
  window->SetMultiSamples(0);
  window->SetAlphaBitPlanes(1);
  const double viewport[4] = { 0, 0, 1, 1 };
  vtkSmartPointer<vtkPARCVolumeMapper> mapper = parctest::AddVolume(
    window, viewport, image, parctest::MakeProperty(true), vtkVolumeMapper::COMPOSITE_BLEND);
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  const double* bounds = image->GetBounds();
  const double translucent[3] = { bounds[1], 0.5 * (bounds[2] + bounds[3]), bounds[5] };
  const double opaque[3] = { bounds[0], bounds[2], 0.5 * (bounds[4] + bounds[5]) };
  AddSphere(renderer, translucent, 0.3 * (bounds[1] - bounds[0]), 0.4);
  AddSphere(renderer, opaque, 0.2 * (bounds[1] - bounds[0]), 1.0);
  renderer->ResetCamera();
  renderer->SetUseDepthPeeling(1);
  renderer->SetMaximumNumberOfPeels(8);
  renderer->SetOcclusionRatio(0.0);

  renderer->SetUseDepthPeelingForVolumes(0);
  const std::vector<unsigned char> reference = Pixels(window);
  const double referenceAlpha = parctest::MaxAlpha(mapper);
  renderer->SetUseDepthPeelingForVolumes(1);
  bool ok = referenceAlpha > 0.5;
  for (int frame = 0; frame < 3; ++frame)
  {
    const std::vector<unsigned char> peeled = Pixels(window);
    std::size_t differing = 0;
    for (std::size_t i = 0; i < peeled.size(); ++i)
    {
      differing += peeled[i] != reference[i];
    }
    if (differing > 0 || !(parctest::MaxAlpha(mapper) == referenceAlpha))
    {
      std::cerr << "frame " << frame << " with UseDepthPeelingForVolumes: " << differing
                << " of " << peeled.size() << " pixel values differ from the frame without it\n";
      ok = false;
    }
  }
  if (!(referenceAlpha > 0.5))
  {
    std::cerr << "the volume does not show (largest alpha " << referenceAlpha << ")\n";
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
