// Interaction under a render-time budget, as a vtkFixedPointVolumeRayCastMapper program
// has it: AutoAdjustSampleDistances on (the default), a render window that asks for 1000
// frames per second while the user drags (no render fits that budget) and for a still
// frame when the drag ends, and a progress bar fed by VolumeMapperRenderProgressEvent.
// Both mappers must coarsen the interactive frames (image sample distance above 1) and
// report progress; their still frames are compared. The wavelet at sample distance 0.5.
#include "parcExampleHarness.h"

#include <vtkCallbackCommand.h>
#include <vtkFixedPointVolumeRayCastMapper.h>

namespace
{
/// The desired update rates of vtkRenderWindowInteractor while dragging and when still.
constexpr double DraggingRate = 1000.0;
constexpr double StillRate = 0.0001;

/// The image sample distance the mapper's last render used.
double LastImageSampleDistance(vtkPARCVolumeMapper* mapper)
{
  return mapper->GetLastImageSampleDistance();
}
double LastImageSampleDistance(vtkFixedPointVolumeRayCastMapper* mapper)
{
  return mapper->GetImageSampleDistance(); // FixedPoint adjusts this setting in place
}

/// Renders two dragging frames and a still one; returns the still image, or null when the
/// mapper did not coarsen the dragging frames or reported no progress.
template <class Mapper>
vtkSmartPointer<vtkImageData> Interact()
{
  vtkNew<Mapper> mapper;
  int progressEvents = 0;
  vtkNew<vtkCallbackCommand> progress;
  progress->SetClientData(&progressEvents);
  progress->SetCallback(
    [](vtkObject*, unsigned long, void* events, void*) { ++*static_cast<int*>(events); });
  mapper->AddObserver(vtkCommand::VolumeMapperRenderProgressEvent, progress);
  auto window = parcexample::MakeWindow([&mapper](vtkRenderer* renderer) {
    mapper->SetInputData(parcexample::MakeWavelet());
    mapper->SetSampleDistance(0.5);
    parcexample::AddVolume(renderer, mapper, parcexample::MakeWaveletProperty());
  });
  window->SetDesiredUpdateRate(DraggingRate);
  window->Render(); // the first frame measures what a frame costs
  window->Render();
  const double dragging = LastImageSampleDistance(mapper);
  window->SetDesiredUpdateRate(StillRate);
  window->Render();
  const double still = LastImageSampleDistance(mapper);
  std::cout << mapper->GetClassName() << ": image sample distance " << dragging
            << " while dragging, " << still << " still; " << progressEvents
            << " progress events\n";
  return dragging > 1.0 && still == 1.0 && progressEvents > 0 ? parcexample::Grab(window)
                                                               : nullptr;
}
}

int main(int, char*[])
{
  auto parcImage = Interact<vtkPARCVolumeMapper>();
  auto vtkImage = Interact<vtkFixedPointVolumeRayCastMapper>();
  return parcImage && vtkImage &&
      parcexample::Close("InteractionBudget, still frames against FixedPoint", parcImage,
        vtkImage, parcexample::AgainstFixedPoint)
    ? EXIT_SUCCESS
    : EXIT_FAILURE;
}
