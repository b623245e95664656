#include "parcRenderTools.h"

#include "vtkPARCVolumeMapper.h"

#include <vtkDataArray.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkCommand.h>
#include <vtkTimerLog.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstdio>

namespace parctools
{
double TimedRender(vtkRenderWindow* window)
{
  const double start = vtkTimerLog::GetUniversalTime();
  window->Render();
  window->WaitForCompletion();
  return vtkTimerLog::GetUniversalTime() - start;
}

void WarmUp(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper)
{
  constexpr int MaxWarmUpRenders = 12;
  int renders = 0;
  do
  {
    window->Render();
  } while (mapper->GetAutoTrialsRemaining() > 0 && ++renders < MaxWarmUpRenders);
}

std::vector<float> RayImage(vtkPARCVolumeMapper* mapper)
{
  vtkNew<vtkImageData> image;
  mapper->GetLastRayCastImage(image);
  auto* rgba = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  return std::vector<float>(
    rgba->GetPointer(0), rgba->GetPointer(0) + 4 * rgba->GetNumberOfTuples());
}

std::vector<unsigned char> WindowPixels(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkDataArray* rgb = grab->GetOutput()->GetPointData()->GetScalars();
  const auto* p = static_cast<const unsigned char*>(rgb->GetVoidPointer(0));
  return std::vector<unsigned char>(p, p + 3 * rgb->GetNumberOfTuples());
}

std::pair<double, double> MinMedian(std::vector<double> times)
{
  std::sort(times.begin(), times.end());
  return { times.front(), times[times.size() / 2] };
}

vtkSmartPointer<vtkFixedPointVolumeRayCastMapper> FixedPointLike(
  vtkPARCVolumeMapper* parc, vtkImageData* image)
{
  auto fixed = vtkSmartPointer<vtkFixedPointVolumeRayCastMapper>::New();
  fixed->SetInputData(image);
  fixed->SetBlendMode(parc->GetBlendMode());
  fixed->SetAutoAdjustSampleDistances(0);
  fixed->SetLockSampleDistanceToInputSpacing(0);
  fixed->SetSampleDistance(parc->GetLastSampleDistance());
  fixed->SetImageSampleDistance(1.0);
  return fixed;
}

vtkSmartPointer<vtkPARCVolumeMapper> CopyMapper(vtkPARCVolumeMapper* parc, int mode)
{
  auto m = vtkSmartPointer<vtkPARCVolumeMapper>::New();
  for (int port = 0; port < parc->GetNumberOfInputPorts(); ++port)
  {
    if (parc->GetNumberOfInputConnections(port) > 0)
    {
      m->SetInputDataObject(port, parc->GetInputDataObject(port, 0));
      m->SetInputBlendMode(port, parc->GetInputBlendMode(port));
    }
  }
  m->SetBlendMode(parc->GetBlendMode());
  m->SetSampleDistance(parc->GetLastSampleDistance());
  m->SetSupercellSize(parc->GetSupercellSize());
  m->SetAutoSupercellSize(parc->GetAutoSupercellSize());
  m->SetShadingModel(parc->GetShadingModel());
  m->SetAmbientModel(parc->GetAmbientModel());
  m->SetAccelerationMode(mode);
  return m;
}

ProgressLine::ProgressLine(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, bool always)
  : Window(window)
  , Mapper(mapper)
  , Always(always)
{
  this->Tags[0] = window->AddObserver(vtkCommand::StartEvent, this, &ProgressLine::OnStart);
  this->Tags[1] = mapper->AddObserver(vtkCommand::ProgressEvent, this, &ProgressLine::OnProgress);
  this->Tags[2] = window->AddObserver(vtkCommand::EndEvent, this, &ProgressLine::OnEnd);
}

ProgressLine::~ProgressLine()
{
  this->Window->RemoveObserver(this->Tags[0]);
  this->Mapper->RemoveObserver(this->Tags[1]);
  this->Window->RemoveObserver(this->Tags[2]);
}

void ProgressLine::OnStart()
{
  this->Start = vtkTimerLog::GetUniversalTime();
  this->Shown = false;
}

void ProgressLine::OnProgress()
{
  if (!this->Always && vtkTimerLog::GetUniversalTime() - this->Start < Delay)
  {
    return;
  }
  const char* text = this->Mapper->GetProgressText();
  std::fprintf(stderr, "\rparc-render: %-28s %3.0f%%", text ? text : "",
    100.0 * this->Mapper->GetProgress());
  std::fflush(stderr);
  this->Shown = true;
}

void ProgressLine::OnEnd()
{
  if (this->Shown)
  {
    std::fputc('\n', stderr);
    this->Shown = false;
  }
}
}
