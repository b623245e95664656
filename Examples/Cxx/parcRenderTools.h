// PARC for VTK examples: what parc-render's measurements share (timed renders, the window's
// pixels, VTK's mappers set up like this one).
#ifndef parcRenderTools_h
#define parcRenderTools_h

#include <vtkSmartPointer.h>

#include <string>
#include <utility>
#include <vector>

class vtkFixedPointVolumeRayCastMapper;
class vtkImageData;
class vtkPARCVolumeMapper;
class vtkRenderWindow;

namespace parctools
{
/// Wall time of one window->Render(), until the GL work is done.
double TimedRender(vtkRenderWindow* window);

/// Renders until the set-up is done: classification, models, GL resources and, in Auto,
/// the trial frames that pick the pass.
void WarmUp(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper);

/// The mapper's last float ray-cast image (RGBA, 4 floats a pixel).
std::vector<float> RayImage(vtkPARCVolumeMapper* mapper);

/// The window's RGB, 8 bits a channel.
std::vector<unsigned char> WindowPixels(vtkRenderWindow* window);

/// The minimum and median of times (not empty).
std::pair<double, double> MinMedian(std::vector<double> times);

/// vtkFixedPointVolumeRayCastMapper on image with parc's blend mode and last sample
/// distance, one ray per pixel, no automatic adjustment.
vtkSmartPointer<vtkFixedPointVolumeRayCastMapper> FixedPointLike(
  vtkPARCVolumeMapper* parc, vtkImageData* image);

/// A mapper like parc (the inputs and ray functions of every port, the sample distance,
/// supercell size and shading model) in acceleration mode.
vtkSmartPointer<vtkPARCVolumeMapper> CopyMapper(vtkPARCVolumeMapper* parc, int mode);
}

#endif
