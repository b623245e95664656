#include "parcViewer.h"

#include "vtkPARCVolumeMapper.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkInteractorEventRecorder.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkVolumeMapper.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <string>

namespace parcviewer
{
namespace
{
constexpr std::array<int, 6> Blends = { vtkVolumeMapper::COMPOSITE_BLEND,
  vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND,
  vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, vtkVolumeMapper::ADDITIVE_BLEND,
  vtkVolumeMapper::ISOSURFACE_BLEND };
const std::array<const char*, 6> BlendNames = { "composite", "mip", "minip", "average",
  "additive", "iso" };
const std::array<std::string, 5> Presets = { "ramp", "mri", "ct-skin-bone", "ct-bone", "mip" };
constexpr std::array<int, 6> Accelerations = { vtkPARCVolumeMapper::ACCELERATION_AUTO,
  vtkPARCVolumeMapper::ACCELERATION_NONE, vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER,
  vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER, vtkPARCVolumeMapper::ACCELERATION_BOTH,
  vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK };
const std::array<const char*, 3> ShadingNames = { "unshaded", "shaded, exact",
  "shaded, quantized normals" };
/// The still frame's image sample distances '+' and '-' step through.
constexpr std::array<double, 5> ImageSampleDistances = { 1.0, 1.5, 2.0, 3.0, 4.0 };
constexpr int StatusFontSize = 13;

/// The entry after `value` in `values`, wrapping (the first when value is not there).
template <class Values, class Value>
auto NextOf(const Values& values, const Value& value)
{
  auto it = std::find(std::begin(values), std::end(values), value);
  return it == std::end(values) || std::next(it) == std::end(values) ? *std::begin(values)
                                                                      : *std::next(it);
}

template <class Values>
std::size_t IndexOf(const Values& values, int value)
{
  return static_cast<std::size_t>(
    std::find(std::begin(values), std::end(values), value) - std::begin(values));
}

/// The viewer's session: the scene, the state the keys set, the status line.
struct Session
{
  const Settings& Options;
  vtkRenderWindow* Window;
  vtkPARCVolumeMapper* Mapper;
  vtkVolumeProperty* Property;
  State& Current;
  vtkNew<vtkTextActor> Status;
  std::string LastMessage; ///< the mapper's last error or warning, shown until the next key
  int Frames = 0;
  int InteractiveFrames = 0;
  int Screenshots = 0;

  void Apply()
  {
    this->Mapper->SetBlendMode(this->Current.Blend);
    this->Options.SetUp(this->Current.Blend, this->Current.TF, this->Property);
    const bool iso = this->Current.Blend == vtkVolumeMapper::ISOSURFACE_BLEND;
    if (iso && this->Current.Shading == 0)
    {
      this->Current.Shading = 1; // an isosurface is always shaded
    }
    this->Property->SetShade(this->Current.Shading > 0);
    this->Mapper->SetShadingModel(this->Current.Shading == 2
        ? vtkPARCVolumeMapper::SHADING_QUANTIZED_NORMALS
        : vtkPARCVolumeMapper::SHADING_EXACT);
    this->Mapper->SetAccelerationMode(this->Current.Acceleration);
    this->Mapper->SetMinimumImageSampleDistance(this->Current.ImageSampleDistance);
    this->Mapper->SetImageSampleDistance(this->Current.ImageSampleDistance);
  }

  /// Handles a key; false for keys the viewer leaves to the trackball style.
  bool Key(const std::string& key)
  {
    State& s = this->Current;
    if (key == "b")
    {
      s.Blend = NextOf(Blends, s.Blend);
    }
    else if (key == "t")
    {
      s.TF = NextOf(Presets, s.TF);
    }
    else if (key == "l")
    {
      s.Shading = (s.Shading + 1) % static_cast<int>(ShadingNames.size());
    }
    else if (key == "a")
    {
      s.Acceleration = NextOf(Accelerations, s.Acceleration);
    }
    else if (key == "plus" || key == "equal" || key == "minus")
    {
      const auto& d = ImageSampleDistances;
      const std::size_t i = static_cast<std::size_t>(
        std::lower_bound(d.begin(), d.end(), s.ImageSampleDistance) - d.begin());
      s.ImageSampleDistance = key == "minus" ? d[std::min(i + 1, d.size() - 1)]
                                             : d[i == 0 ? 0 : std::min(i, d.size()) - 1];
    }
    else if (key == "c")
    {
      this->Screenshot();
      return true;
    }
    else if (key == "h")
    {
      std::cout << Help() << std::flush;
      return true;
    }
    else
    {
      return false;
    }
    this->LastMessage.clear();
    this->Apply();
    this->Window->Render();
    return true;
  }

  /// Writes the window's image without the status line.
  void Screenshot()
  {
    this->Status->VisibilityOff();
    this->Window->Render();
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(this->Window);
    grab->ReadFrontBufferOff();
    vtkNew<vtkPNGWriter> writer;
    const std::string name =
      this->Options.ScreenshotPrefix + "-" + std::to_string(++this->Screenshots) + ".png";
    writer->SetFileName(name.c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    this->Status->VisibilityOn();
    this->Window->Render();
    std::cout << (writer->GetErrorCode() == 0 ? "wrote " : "cannot write ") << name << std::endl;
  }

  /// The status line of the render that just cast (the text is drawn after the volume).
  void UpdateStatus()
  {
    vtkPARCVolumeMapper* m = this->Mapper;
    this->InteractiveFrames += m->GetLastInteractive() ? 1 : 0;
    const State& s = this->Current;
    char line[512];
    std::snprintf(line, sizeof(line), "%s | %s | %s\n%s%s | cast %.3f s | %.2f M samples",
      BlendNames[IndexOf(Blends, s.Blend)], s.TF.empty() ? "default colours" : s.TF.c_str(),
      ShadingNames[static_cast<std::size_t>(s.Shading)],
      vtkPARCVolumeMapper::GetAccelerationModeAsString(m->GetLastAccelerationMode()),
      m->GetAccelerationMode() == vtkPARCVolumeMapper::ACCELERATION_AUTO ? " (Auto)" : "",
      m->GetLastCastingTime(), 1e-6 * static_cast<double>(m->GetLastSampleCount()));
    std::string text = line;
    std::snprintf(line, sizeof(line), "image sample distance %.1f",
      m->GetLastImageSampleDistance());
    text += m->GetLastInteractive() ? std::string("\ninteractive frame, ") + line
                                    : std::string("\nexact still frame, ") + line;
    if (!this->LastMessage.empty())
    {
      text += "\n" + this->LastMessage;
    }
    this->Status->SetInput(text.c_str());
  }
};

/// The trackball camera, with the viewer's keys taken first.
class ViewerStyle : public vtkInteractorStyleTrackballCamera
{
public:
  static ViewerStyle* New();
  vtkTypeMacro(ViewerStyle, vtkInteractorStyleTrackballCamera);
  Session* Viewer = nullptr;

  void OnChar() override
  {
    const char* sym = this->Interactor->GetKeySym();
    if (!this->Viewer || !sym || !this->Viewer->Key(sym))
    {
      this->Superclass::OnChar();
    }
  }
};
vtkStandardNewMacro(ViewerStyle);

template <class Callback>
void Observe(vtkObject* object, unsigned long event, Callback* callback, Session* session)
{
  vtkNew<vtkCallbackCommand> command;
  command->SetCallback(callback);
  command->SetClientData(session);
  object->AddObserver(event, command);
}
}

std::string Help()
{
  return "keys: mouse drag rotates (left), pans (middle), zooms (right or wheel)\n"
         "  b  next blend mode (composite, mip, minip, average, additive, iso)\n"
         "  t  next transfer-function preset (ramp, mri, ct-skin-bone, ct-bone, mip)\n"
         "  l  shading: unshaded, exact, quantized normals\n"
         "  a  next acceleration mode (auto, none, depth, color, both, walk)\n"
         "  +  finer still frame (image sample distance down to 1)\n"
         "  -  coarser still frame (image sample distance up to 4)\n"
         "  c  screenshot (PNG)\n"
         "  h  this help\n"
         "  q  quit\n";
}

Frames Run(const Settings& settings, vtkRenderWindow* window, vtkRenderer* renderer,
  vtkPARCVolumeMapper* mapper, vtkVolumeProperty* property, State& state)
{
  Session session{ settings, window, mapper, property, state, {}, {}, 0, 0, 0 };
  session.Apply();
  session.Status->GetTextProperty()->SetFontSize(StatusFontSize);
  session.Status->GetTextProperty()->SetColor(1.0, 1.0, 0.6);
  session.Status->SetPosition(8, 8);
  session.Status->SetInput("first frame");
  renderer->AddActor2D(session.Status);

  Observe(mapper, vtkCommand::VolumeMapperRenderEndEvent,
    +[](vtkObject*, unsigned long, void* data, void*) {
      static_cast<Session*>(data)->UpdateStatus();
    },
    &session);
  const auto remember = +[](vtkObject*, unsigned long, void* data, void* message) {
    std::string text = message ? static_cast<const char*>(message) : "";
    const std::size_t end = text.find('\n');
    static_cast<Session*>(data)->LastMessage = text.substr(0, end);
  };
  Observe(mapper, vtkCommand::ErrorEvent, remember, &session);
  Observe(mapper, vtkCommand::WarningEvent, remember, &session);
  Observe(window, vtkCommand::EndEvent,
    +[](vtkObject*, unsigned long, void* data, void*) { ++static_cast<Session*>(data)->Frames; },
    &session);

  vtkNew<vtkRenderWindowInteractor> interactor;
  vtkNew<ViewerStyle> style;
  style->Viewer = &session;
  interactor->SetInteractorStyle(style);
  interactor->SetDesiredUpdateRate(settings.InteractiveRate);
  interactor->SetRenderWindow(window);
  interactor->Initialize();
  window->Render();
  if (settings.Playback.empty())
  {
    std::cout << Help() << std::flush;
    interactor->Start();
  }
  else
  {
    vtkNew<vtkInteractorEventRecorder> recorder;
    recorder->SetInteractor(interactor);
    recorder->SetFileName(settings.Playback.c_str());
    recorder->Play();
    recorder->Off();
  }
  style->Viewer = nullptr;
  return { session.Frames, session.InteractiveFrames };
}
}
