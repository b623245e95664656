// PARC for VTK examples: what accuracy costs in time (parc-render --accuracy-curve).
//
// Every mapper that can render the scene (this one in each acceleration mode, with each
// shading model when shaded; vtkFixedPointVolumeRayCastMapper; vtkGPUVolumeRayCastMapper)
// renders it at sample distances from 2 voxels down to Settings::FinestDistance and at
// image sample distances 1 and 2, warm frames interleaved across the mappers. VolPack joins
// at sample distance 1 (one sample per slice) where its model allows the scene
// (parcVolPack.h). Each image is compared with the reference, this mapper's exact cast at
// Settings::ReferenceDistance, whose convergence is shown first (casts at 4 and 2 times its
// distance against it), and with the mapper's own image at the reference distance, so that
// sampling error and model differences can be told apart. Markdown on stdout; one CSV row
// per measurement.
#ifndef parcAccuracyStudy_h
#define parcAccuracyStudy_h

#include <string>

class vtkImageData;
class vtkPARCVolumeMapper;
class vtkRenderWindow;
class vtkVolume;

namespace parcaccuracy
{
struct Settings
{
  int Rounds = 3;                       ///< timed frames per mapper and setting
  double FinestDistance = 1.0 / 16.0;   ///< the curve's last sample distance (voxels)
  double ReferenceDistance = 1.0 / 64.0; ///< the reference's sample distance (voxels)
  std::string Csv;                      ///< file the rows are appended to (empty: none)
  std::string Scene = "scene";          ///< the scene's name in the CSV
};

/// The study of the scene in window: volume, rendered by parc, of image. The CSV columns:
/// scene, mapper, image_sample_distance, sample_distance (voxels), median_s, min_s, max_s,
/// rmse, max_error (8-bit RGB against the reference), rmse_own (against the mapper's own
/// image at the reference distance; empty for VolPack), float_rmse (this mapper's float
/// RGBA against the reference's, in 1/255; empty for other mappers and image sample
/// distance 2).
void Study(const Settings& settings, vtkRenderWindow* window, vtkVolume* volume,
  vtkPARCVolumeMapper* parc, vtkImageData* image);
}

#endif
