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

/// A progress line on stderr for the renders of a window while it lives: the mapper's
/// progress text and percentage (its ProgressEvent), rewritten in place and ended with the
/// render. Always, or only for renders that have run longer than Delay (a long set-up).
class ProgressLine
{
public:
  static constexpr double Delay = 1.0; ///< seconds
  ProgressLine(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, bool always);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

private:
  void OnStart();
  void OnProgress();
  void OnEnd();

  vtkRenderWindow* Window;
  vtkPARCVolumeMapper* Mapper;
  bool Always;
  double Start = 0.0;
  bool Shown = false;
  unsigned long Tags[3] = { 0, 0, 0 };
};
}

#endif
