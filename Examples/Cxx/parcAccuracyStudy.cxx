#include "parcAccuracyStudy.h"

#include "parcRenderTools.h"
#include "parcVolPack.h"
#include "vtkPARCVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkSmartPointer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace parcaccuracy
{
namespace
{
using parctools::MinMedian;
using parctools::RayImage;
using parctools::TimedRender;
using parctools::WindowPixels;

/// Image sample distances of the study: one ray per pixel, and one per 2x2 pixels.
constexpr double ImageSampleDistances[] = { 1.0, 2.0 };
/// The coarsest sample distance of the curve, in voxels; each next one is half.
constexpr double CoarsestDistance = 2.0;

/// One mapper of the study and its image at the reference distance.
struct Contender
{
  std::string Name;
  vtkSmartPointer<vtkVolumeMapper> Mapper;
  vtkPARCVolumeMapper* Parc = nullptr; ///< this mapper (null: one of VTK's)
  bool Exact = false; ///< this mapper with exact shading: its own image is the reference
  std::vector<unsigned char> Own;
};

/// A contender's image at one setting and its frame times.
struct Frame
{
  std::vector<unsigned char> Pixels;
  std::vector<float> Ray; ///< this mapper's float image (image sample distance 1)
  std::vector<double> Times;
};

struct ImageError
{
  double Rmse = 0.0;
  double Max = 0.0;
};

/// RMSE and largest difference of two 8-bit images, in grey levels.
ImageError Compare(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  ImageError e;
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i)
  {
    const double d = std::abs(static_cast<double>(a[i]) - static_cast<double>(b[i]));
    e.Rmse += d * d;
    e.Max = std::max(e.Max, d);
  }
  e.Rmse = std::sqrt(e.Rmse / std::max<std::size_t>(n, 1));
  return e;
}

/// RMSE of two float RGBA images in units of 1/255 (-1 when their sizes differ).
double FloatRmse(const std::vector<float>& a, const std::vector<float>& b)
{
  if (a.size() != b.size() || a.empty())
  {
    return -1.0;
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    const double d = static_cast<double>(a[i]) - static_cast<double>(b[i]);
    sum += d * d;
  }
  return 255.0 * std::sqrt(sum / a.size());
}

/// Sets one of VTK's mappers to a world sample distance and an image sample distance,
/// without automatic adjustment.
template <class Mapper>
void ConfigureVTK(Mapper* m, double world, double imageSampleDistance)
{
  m->SetAutoAdjustSampleDistances(0);
  m->SetLockSampleDistanceToInputSpacing(0);
  m->SetSampleDistance(world);
  m->SetImageSampleDistance(imageSampleDistance);
}

void Configure(Contender& c, double world, double imageSampleDistance)
{
  if (c.Parc)
  {
    c.Parc->SetAutoAdjustSampleDistances(0);
    c.Parc->SetSampleDistance(world);
    c.Parc->SetImageSampleDistance(imageSampleDistance);
  }
  else if (auto* fixed = vtkFixedPointVolumeRayCastMapper::SafeDownCast(c.Mapper))
  {
    ConfigureVTK(fixed, world, imageSampleDistance);
  }
  else if (auto* gpu = vtkGPUVolumeRayCastMapper::SafeDownCast(c.Mapper))
  {
    ConfigureVTK(gpu, world, imageSampleDistance);
  }
}

/// Renders c's first frame at the current setting (for this mapper, until Auto has
/// settled): its pixels, and its float image when wanted.
Frame FirstFrame(vtkRenderWindow* window, vtkVolume* volume, Contender& c, bool withRay)
{
  volume->SetMapper(c.Mapper);
  if (c.Parc)
  {
    parctools::WarmUp(window, c.Parc);
  }
  else
  {
    window->Render();
  }
  Frame f;
  f.Pixels = WindowPixels(window);
  if (c.Parc && withRay)
  {
    f.Ray = RayImage(c.Parc);
  }
  return f;
}

/// The contenders for the scene: this mapper in every acceleration mode (parc itself is
/// Auto), with quantized normals when shaded, and VTK's mappers where they have the blend
/// mode and can render here.
std::vector<Contender> Contenders(
  vtkRenderWindow* window, vtkVolume* volume, vtkPARCVolumeMapper* parc, vtkImageData* image)
{
  std::vector<Contender> all;
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_NONE,
    vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER, vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_BOTH };
  parc->SetShadingModelToExact();
  for (int mode : modes)
  {
    auto copy = parctools::CopyMapper(parc, mode);
    all.push_back({ std::string("PARC ") + vtkPARCVolumeMapper::GetAccelerationModeAsString(mode),
      copy, copy.Get(), true, {} });
  }
  all.push_back({ "PARC Auto", parc, parc, true, {} });
  if (volume->GetProperty()->GetShade())
  {
    auto quantized = parctools::CopyMapper(parc, vtkPARCVolumeMapper::ACCELERATION_AUTO);
    quantized->SetShadingModelToQuantizedNormals();
    all.push_back({ "PARC Auto, quantized normals", quantized, quantized.Get(), false, {} });
  }
  const int blend = parc->GetBlendMode();
  if (blend != vtkVolumeMapper::ISOSURFACE_BLEND &&
    blend != vtkVolumeMapper::AVERAGE_INTENSITY_BLEND)
  {
    all.push_back({ "vtkFixedPointVolumeRayCastMapper", parctools::FixedPointLike(parc, image),
      nullptr, false, {} });
  }
  auto gpu = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
  gpu->SetInputData(image);
  gpu->SetBlendMode(blend);
  if (gpu->IsRenderSupported(window, volume->GetProperty()))
  {
    all.push_back({ "vtkGPUVolumeRayCastMapper (llvmpipe)", gpu, nullptr, false, {} });
  }
  else
  {
    std::printf("vtkGPUVolumeRayCastMapper cannot render here; left out.\n\n");
  }
  return all;
}

/// The reference and the casts at 4 and 2 times its distance against it (markdown).
void ShowConvergence(vtkRenderWindow* window, vtkVolume* volume, Contender& parcAuto,
  double voxel, double reference, const Frame& ref)
{
  std::printf("Reference: this mapper's exact cast at %g voxel. Its convergence, against "
              "it:\n\n| sample distance (voxels) | RMSE | max | float RMSE (1/255) |\n"
              "|---|---|---|---|\n",
    reference);
  for (double factor : { 4.0, 2.0 })
  {
    Configure(parcAuto, factor * reference * voxel, 1.0);
    const Frame f = FirstFrame(window, volume, parcAuto, true);
    const ImageError e = Compare(f.Pixels, ref.Pixels);
    std::printf("| %g | %.3f | %.0f | %.4f |\n", factor * reference, e.Rmse, e.Max,
      FloatRmse(f.Ray, ref.Ray));
  }
  std::printf("\n");
}

/// VolPack in the tables, and the sample distance it stands at (one sample per slice).
constexpr const char* VolPackName = "VolPack (shear-warp, 1 thread)";
constexpr double VolPackDistance = 1.0;

/// One measurement: a contender's frame at a setting, and its error against its own image
/// at the reference distance (negative: it has no other setting).
struct Row
{
  double ImageSampleDistance;
  double Distance;
  std::string Name;
  const Frame* F;
  double OwnRmse;

  /// Prints the markdown row, and the CSV row when csv is open.
  void Print(const Frame& ref, const std::string& scene, std::ofstream& csv) const
  {
    const auto [fastest, median] = MinMedian(this->F->Times);
    const double slowest = *std::max_element(this->F->Times.begin(), this->F->Times.end());
    const ImageError e = Compare(this->F->Pixels, ref.Pixels);
    const double floatRmse = FloatRmse(this->F->Ray, ref.Ray);
    char floatText[32] = "", ownText[32] = "";
    if (floatRmse >= 0.0)
    {
      std::snprintf(floatText, sizeof(floatText), "%.4f", floatRmse);
    }
    if (this->OwnRmse >= 0.0)
    {
      std::snprintf(ownText, sizeof(ownText), "%.3f", this->OwnRmse);
    }
    std::printf("| %g | %g | %s | %.4f | %.4f-%.4f | %.3f | %.0f | %s | %s |\n",
      this->ImageSampleDistance, this->Distance, this->Name.c_str(), median, fastest, slowest,
      e.Rmse, e.Max, ownText, floatText);
    if (csv.is_open())
    {
      csv << "\"" << scene << "\",\"" << this->Name << "\"," << this->ImageSampleDistance << ","
          << this->Distance << "," << median << "," << fastest << "," << slowest << "," << e.Rmse
          << "," << e.Max << "," << ownText << "," << floatText << "\n";
    }
  }
};

/// Opens the CSV for appending; writes the header when the file is new.
std::ofstream OpenCsv(const std::string& path)
{
  std::ifstream existing(path);
  const bool fresh = !existing.good() || existing.peek() == std::ifstream::traits_type::eof();
  std::ofstream csv(path, std::ios::app);
  if (fresh)
  {
    csv << "scene,mapper,image_sample_distance,sample_distance,median_s,min_s,max_s,rmse,"
           "max_error,rmse_own,float_rmse\n";
  }
  return csv;
}
}

void Study(const Settings& settings, vtkRenderWindow* window, vtkVolume* volume,
  vtkPARCVolumeMapper* parc, vtkImageData* image)
{
  const double* spacing = image->GetSpacing();
  const double voxel = std::min({ spacing[0], spacing[1], spacing[2] });
  const double savedDistance = parc->GetSampleDistance();
  const double savedImageDistance = parc->GetImageSampleDistance();
  const vtkTypeBool savedAdjust = parc->GetAutoAdjustSampleDistances();
  std::vector<Contender> all = Contenders(window, volume, parc, image);
  Contender& autoContender =
    *std::find_if(all.begin(), all.end(), [parc](const Contender& c) { return c.Parc == parc; });

  Configure(autoContender, settings.ReferenceDistance * voxel, 1.0);
  const Frame ref = FirstFrame(window, volume, autoContender, true);
  ShowConvergence(window, volume, autoContender, voxel, settings.ReferenceDistance, ref);
  for (Contender& c : all)
  {
    if (c.Exact)
    {
      c.Own = ref.Pixels;
      continue;
    }
    Configure(c, settings.ReferenceDistance * voxel, 1.0);
    c.Own = FirstFrame(window, volume, c, false).Pixels;
  }

  vtkCamera* camera = window->GetRenderers()->GetFirstRenderer()->GetActiveCamera();
  const int* size = window->GetSize();
  std::unique_ptr<parcvolpack::Renderer> volpack;
  const std::string volpackMissing =
    parcvolpack::Renderer::Unsupported(parc->GetBlendMode(), volume, image, camera);
  if (volpackMissing.empty())
  {
    volpack = std::make_unique<parcvolpack::Renderer>(volume, image);
    std::printf("VolPack classified the volume in %.3f s (once per transfer function; not in "
                "its frame times).\n\n",
      volpack->ClassificationTime());
  }
  else
  {
    std::printf("VolPack is left out: %s.\n\n", volpackMissing.c_str());
  }

  std::ofstream csv;
  if (!settings.Csv.empty())
  {
    csv = OpenCsv(settings.Csv);
  }
  std::printf("| image sample distance | sample distance (voxels) | mapper | median (s) | "
              "min-max (s) | RMSE | max | RMSE against its own | float RMSE (1/255) |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  for (double isd : ImageSampleDistances)
  {
    for (double d = CoarsestDistance; d >= settings.FinestDistance * (1.0 - 1e-9); d /= 2.0)
    {
      std::vector<Frame> frames;
      for (Contender& c : all)
      {
        Configure(c, d * voxel, isd);
        frames.push_back(FirstFrame(window, volume, c, isd == 1.0));
      }
      // VolPack samples once per slice: it stands at sample distance 1, one ray a pixel.
      Frame volpackFrame;
      if (volpack && isd == 1.0 && d == VolPackDistance)
      {
        double seconds;
        volpackFrame.Pixels = volpack->Render(camera, size[0], size[1], seconds);
      }
      for (int r = 0; r < settings.Rounds; ++r) // interleaved: A B C A B C ...
      {
        for (std::size_t i = 0; i < all.size(); ++i)
        {
          volume->SetMapper(all[i].Mapper);
          frames[i].Times.push_back(TimedRender(window));
        }
        if (!volpackFrame.Pixels.empty())
        {
          volpackFrame.Times.push_back(0.0);
          volpack->Render(camera, size[0], size[1], volpackFrame.Times.back());
        }
      }
      for (std::size_t i = 0; i < all.size(); ++i)
      {
        Row row{ isd, d, all[i].Name, &frames[i], Compare(frames[i].Pixels, all[i].Own).Rmse };
        row.Print(ref, settings.Scene, csv);
      }
      if (!volpackFrame.Pixels.empty())
      {
        Row{ isd, d, VolPackName, &volpackFrame, -1.0 }.Print(ref, settings.Scene, csv);
      }
    }
  }
  std::printf("\n%d interleaved rounds per setting after a first frame (Auto's trials); "
              "Auto used %s at the last\n",
    settings.Rounds,
    vtkPARCVolumeMapper::GetAccelerationModeAsString(parc->GetLastAccelerationMode()));
  parc->SetSampleDistance(savedDistance);
  parc->SetImageSampleDistance(savedImageDistance);
  parc->SetAutoAdjustSampleDistances(savedAdjust);
  volume->SetMapper(parc);
}
}
