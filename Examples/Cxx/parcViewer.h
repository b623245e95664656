// parc-render --interactive: a window on a volume drawn by vtkPARCVolumeMapper, with
// trackball interaction, interactive frames held to a budget and an exact still frame,
// keys that change what is drawn and how, and a status line.
#ifndef parcViewer_h
#define parcViewer_h

#include <functional>
#include <string>

class vtkPARCVolumeMapper;
class vtkRenderWindow;
class vtkRenderer;
class vtkVolumeProperty;

namespace parcviewer
{
/// What the keys change; the viewer starts from these and applies them with Apply.
struct State
{
  int Blend = 0;            ///< vtkVolumeMapper blend mode
  std::string TF;           ///< transfer function preset (empty: the blend mode's default)
  int Shading = 0;          ///< 0 unshaded, 1 exact, 2 quantized normals
  int Acceleration = 0;     ///< vtkPARCVolumeMapper acceleration mode
  double ImageSampleDistance = 1.0; ///< of the still frame
};

struct Settings
{
  double InteractiveRate = 10.0; ///< frames per second while the mouse moves the camera
  /// A vtkInteractorEventRecorder log played instead of a user's events (tests); the
  /// viewer returns when it ends.
  std::string Playback;
  /// Screenshots ('c') are written as Prefix-N.png.
  std::string ScreenshotPrefix = "parc-view";
  /// Sets the property up for a blend mode and a preset (the iso value, shading).
  std::function<void(int blend, const std::string& tf, vtkVolumeProperty* property)> SetUp;
};

/// The keys, one line each (also printed by 'h').
std::string Help();

/// The frames a viewer rendered: all of them, and those the mapper cast as interactive.
struct Frames
{
  int All = 0;
  int Interactive = 0;
};

/// Runs the viewer in window (shown on screen) until the user closes it or the playback
/// ends; state holds what the keys last set.
Frames Run(const Settings& settings, vtkRenderWindow* window, vtkRenderer* renderer,
  vtkPARCVolumeMapper* mapper, vtkVolumeProperty* property, State& state);
}

#endif
