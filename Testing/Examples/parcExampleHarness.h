// The harness of the drop-in example programs in this folder.
//
// Each program is written as a VTK user writes one, in a generic lambda that receives the
// mapper: one program text compiles and runs with vtkPARCVolumeMapper and with the VTK
// mapper it is compared with, which is the one-line swap a user makes. The harness renders
// the scene with each mapper, each in its own off-screen window, and compares the two 8-bit
// images within the tolerance the program states. The samplers differ (VTK's
// fixed-point arithmetic, rays that start on other planes), so the images are not equal;
// the tolerance says how close they are.
//
// Options: -T <dir> writes <name>.png there: this mapper, VTK's and 4x their difference,
// side by side; -I opens this mapper's window for interaction after the comparison; -O
// enables vtkPARCOverrides first (the C++ switch), as PARC_OVERRIDE_GPU_MAPPER=1 does when
// the library loads. With the override on, a program compared with vtkGPUVolumeRayCastMapper
// or vtkSmartVolumeMapper renders its unchanged VTK version through PARC: the harness checks
// that PARC rendered it (its statistics) and that its image equals the one-line-swapped
// program's, value for value.
#ifndef parcExampleHarness_h
#define parcExampleHarness_h

#include "vtkPARCOverrides.h"
#include "vtkPARCVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkImageAppend.h>
#include <vtkImageChangeInformation.h>
#include <vtkImageGaussianSource.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkImageShiftScale.h>
#include <vtkPNGWriter.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRTAnalyticSource.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>

namespace parcexample
{
/// How close this mapper's image must be to VTK's, in 8-bit channel values.
struct Tolerance
{
  double MeanDifference;         ///< mean |difference| over all RGB values
  double FarFraction = 0.001;    ///< fraction of the values allowed beyond FarDifference
  int FarDifference = 24;        ///< what counts as far
};

/// The tolerances against each of VTK's mappers, at sample distance 0.5 and one ray a
/// pixel: FixedPoint's fixed-point arithmetic and tables cost it up to a grey level on
/// average; the GPU mapper's rays start on the box's faces, not on the lattice of planes.
constexpr Tolerance AgainstFixedPoint{ 1.0 };
constexpr Tolerance AgainstGPU{ 2.0 };
/// No value may differ.
constexpr Tolerance Identical{ 0.0, 0.0, 0 };

/// The exit code that tells CTest a program was skipped (its data are absent).
constexpr int SkipCode = 125;
/// The window's width and height in pixels.
constexpr int WindowSize = 200;

/// The examples' volumes: 64^3 voxels over [-32, 31]^3 in world coordinates, with an
/// extent that starts at 0 (VTK 9.1's FixedPoint mapper places cropping planes, and its GPU
/// mapper places a mask, as if every extent started at 0). They are made by sources on the
/// extent -32 to 31, where voxel indices are world coordinates, then moved by ZeroBased.
constexpr int VolumeLow = -32;
constexpr int VolumeHigh = 31;

template <class ImageSource>
void SetVolumeExtent(ImageSource* source)
{
  source->SetWholeExtent(VolumeLow, VolumeHigh, VolumeLow, VolumeHigh, VolumeLow, VolumeHigh);
}

/// The source's output, moved to the extent 0 to 63 at origin -32: the same world
/// positions.
inline vtkSmartPointer<vtkImageData> ZeroBased(vtkAlgorithm* source)
{
  vtkNew<vtkImageChangeInformation> zeroBased;
  zeroBased->SetInputConnection(source->GetOutputPort());
  zeroBased->SetOutputExtentStart(0, 0, 0);
  zeroBased->SetOutputOrigin(VolumeLow, VolumeLow, VolumeLow);
  zeroBased->Update();
  return zeroBased->GetOutput();
}

/// VTK's wavelet (vtkRTAnalyticSource) as unsigned char: 0 to 254, a bright centre in a
/// rippled field. The data most examples start from.
inline vtkSmartPointer<vtkImageData> MakeWavelet()
{
  vtkNew<vtkRTAnalyticSource> wavelet;
  SetVolumeExtent(wavelet.Get());
  vtkNew<vtkImageShiftScale> bytes;
  bytes->SetInputConnection(wavelet->GetOutputPort());
  bytes->SetShift(-32.0); // the wavelet's values run from 32.4 to 285.6 here
  bytes->SetOutputScalarTypeToUnsignedChar();
  bytes->ClampOverflowOn();
  return ZeroBased(bytes);
}

/// A Gaussian blob as unsigned char: 254 at the centre (world coordinates), falling off
/// with the standard deviation sigma (voxels).
inline vtkSmartPointer<vtkImageData> MakeBlob(double x, double y, double z, double sigma)
{
  vtkNew<vtkImageGaussianSource> blob;
  SetVolumeExtent(blob.Get());
  blob->SetCenter(x, y, z);
  blob->SetStandardDeviation(sigma);
  blob->SetMaximum(254.0);
  vtkNew<vtkImageShiftScale> bytes;
  bytes->SetInputConnection(blob->GetOutputPort());
  bytes->SetOutputScalarTypeToUnsignedChar();
  return ZeroBased(bytes);
}

/// The settings under which the examples compare the mappers: no budget adjustment, a
/// sample every 0.5 world units, one ray per pixel.
template <class Mapper>
void SampleAlike(Mapper* mapper)
{
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetLockSampleDistanceToInputSpacing(0);
  mapper->SetSampleDistance(0.5);
  mapper->SetImageSampleDistance(1.0);
}

/// Adds a volume of the mapper and property to the renderer.
inline void AddVolume(vtkRenderer* renderer, vtkAbstractVolumeMapper* mapper,
  vtkVolumeProperty* property)
{
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  renderer->AddVolume(volume);
}

/// A property for the wavelet: the ripples faint and blue, the centre dense and orange.
inline vtkSmartPointer<vtkVolumeProperty> MakeWaveletProperty()
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(90, 0.0);
  opacity->AddPoint(140, 0.03);
  opacity->AddPoint(200, 0.2);
  opacity->AddPoint(254, 0.6);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0, 0.0, 0.0, 0.0);
  color->AddRGBPoint(110, 0.2, 0.4, 1.0);
  color->AddRGBPoint(180, 1.0, 0.6, 0.2);
  color->AddRGBPoint(254, 1.0, 1.0, 0.9);
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetInterpolationTypeToLinear();
  return property;
}

/// The renderer of a scene: a dark background and the view every example starts from,
/// the volumes' bounds turned by 35 degrees azimuth and 25 elevation.
inline void SetUpView(vtkRenderer* renderer)
{
  renderer->SetBackground(0.1, 0.1, 0.15);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(35);
  renderer->GetActiveCamera()->Elevation(25);
  renderer->GetActiveCamera()->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange();
}

/// An off-screen window of WindowSize^2 pixels with one renderer holding the scene.
inline vtkSmartPointer<vtkRenderWindow> MakeWindow(
  const std::function<void(vtkRenderer*)>& scene)
{
  auto window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetSize(WindowSize, WindowSize);
  window->SetMultiSamples(0);
  window->SetOffScreenRendering(1);
  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  scene(renderer);
  SetUpView(renderer);
  return window;
}

/// The window's RGB image, copied.
inline vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}

inline vtkUnsignedCharArray* Values(vtkImageData* image)
{
  return vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
}

/// 4x the absolute difference of two images of the same size, clamped to 255.
inline vtkSmartPointer<vtkImageData> Difference(vtkImageData* a, vtkImageData* b)
{
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(a);
  vtkUnsignedCharArray* d = Values(out);
  for (vtkIdType i = 0; i < d->GetNumberOfValues(); ++i)
  {
    const int diff = std::abs(Values(a)->GetValue(i) - Values(b)->GetValue(i));
    d->SetValue(i, static_cast<unsigned char>(std::min(255, 4 * diff)));
  }
  return out;
}

/// The value of a command-line option such as -T (nullptr when absent).
inline const char* Option(int argc, char* argv[], const char* name)
{
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], name) == 0)
    {
      return argv[i + 1];
    }
  }
  return nullptr;
}

inline bool Flag(int argc, char* argv[], const char* name)
{
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], name) == 0)
    {
      return true;
    }
  }
  return false;
}

/// Writes this mapper's image, VTK's and their difference side by side to <dir>/<name>.png.
inline void WriteSideBySide(const char* dir, const std::string& name, vtkImageData* parc,
  vtkImageData* vtk)
{
  vtkNew<vtkImageAppend> row;
  row->SetAppendAxis(0);
  row->AddInputData(parc);
  row->AddInputData(vtk);
  row->AddInputData(Difference(parc, vtk));
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputConnection(row->GetOutputPort());
  writer->SetFileName((std::string(dir) + "/" + name + ".png").c_str());
  writer->Write();
}

/// Compares two images of one scene within the tolerance and prints the figures. The
/// comparison needs a picture: at least 0.5% of this mapper's values must differ from
/// the background's by more than 16.
inline bool Close(const std::string& what, vtkImageData* parc, vtkImageData* vtk,
  const Tolerance& tolerance)
{
  vtkUnsignedCharArray* a = Values(parc);
  vtkUnsignedCharArray* b = Values(vtk);
  const vtkIdType n = a->GetNumberOfValues();
  if (n == 0 || b->GetNumberOfValues() != n)
  {
    std::cout << what << ": images of different sizes\n";
    return false;
  }
  double sum = 0.0;
  vtkIdType far = 0, drawn = 0;
  const int components = a->GetNumberOfComponents();
  for (vtkIdType i = 0; i < n; ++i)
  {
    const int d = std::abs(a->GetValue(i) - b->GetValue(i));
    sum += d;
    far += d > tolerance.FarDifference;
    drawn += std::abs(a->GetValue(i) - a->GetValue(i % components)) > 16;
  }
  const double mean = sum / n;
  const double farFraction = static_cast<double>(far) / n;
  const bool ok = mean <= tolerance.MeanDifference && farFraction <= tolerance.FarFraction &&
    drawn > n / 200;
  std::cout << what << ": mean |difference| " << mean << " (at most "
            << tolerance.MeanDifference << "), beyond " << tolerance.FarDifference << ": "
            << 100.0 * farFraction << "% (at most " << 100.0 * tolerance.FarFraction
            << "%), drawn values " << drawn << " of " << n << (ok ? "" : "  FAILED") << "\n";
  return ok;
}

/// What a program checks of a mapper after its render, besides the image: nothing.
struct NoCheck
{
  template <class Mapper>
  bool operator()(Mapper*) const
  {
    return true;
  }
};

/// Renders the scene with a vtkPARCVolumeMapper and with a VTKMapper, compares the images
/// and handles -T and -I. scene(renderer, mapper) sets the mapper up and adds its volume:
/// a generic lambda, so that one program text serves both mapper types; check(mapper),
/// called after each render, says whether what else the program expects held. Returns the
/// program's exit code.
template <class VTKMapper, class SceneFunction, class Check = NoCheck>
int CompareWithVTK(int argc, char* argv[], const std::string& name, const SceneFunction& scene,
  const Tolerance& tolerance, const Check& check = Check())
{
  if (Flag(argc, argv, "-O"))
  {
    vtkPARCOverrides::Enable();
  }
  vtkNew<vtkPARCVolumeMapper> parcMapper;
  auto parcWindow = MakeWindow([&](vtkRenderer* r) { scene(r, parcMapper.Get()); });
  parcWindow->Render();
  auto parcImage = Grab(parcWindow);
  bool ok = check(parcMapper.Get());
  vtkNew<VTKMapper> vtkMapper;
  auto vtkWindow = MakeWindow([&](vtkRenderer* r) { scene(r, vtkMapper.Get()); });
  vtkWindow->Render();
  auto vtkImage = Grab(vtkWindow);
  ok = check(vtkMapper.Get()) && ok;
  vtkPARCVolumeMapper* through = vtkPARCOverrides::GetPARCMapper(vtkMapper.Get());
  if (through && through->GetLastSampleCount() > 0)
  {
    // The unchanged VTK program rendered through PARC by the object-factory override (a
    // smart mapper in its ray-cast mode uses its FixedPoint mapper, which no override
    // reaches: compared below as usual).
    std::cout << name << " through the override (" << vtkMapper->GetClassName() << "): "
              << through->GetLastSampleCount() << " PARC samples\n";
    ok = Close(name + " through the override", parcImage, vtkImage, Identical) && ok;
  }
  else
  {
    ok = Close(name + " against " + vtkMapper->GetClassName(), parcImage, vtkImage, tolerance) &&
      ok;
  }
  if (const char* dir = Option(argc, argv, "-T"))
  {
    WriteSideBySide(dir, name, parcImage, vtkImage);
  }
  if (Flag(argc, argv, "-I"))
  {
    parcWindow->SetOffScreenRendering(0);
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(parcWindow);
    interactor->Start();
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
}

#endif
