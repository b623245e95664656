// PARC for VTK examples: VolPack (Lacroute's shear-warp renderer, which the paper cites)
// rendering a VTK scene, for the accuracy study of parc-render.
//
// VolPack's model, and so where it can stand beside the ray casters: 8-bit scalars,
// parallel projection only, one sample per slice along the principal viewing axis
// (its sample distance cannot be chosen), classification of the voxels before resampling
// (opacity and colour tables indexed by the voxel value, opacity stored in 8 bits), and
// lookup-table shading with its own 13-bit normals, one directional light. It has no clipping
// planes, cropping or gradient opacity. Single-threaded.
#ifndef parcVolPack_h
#define parcVolPack_h

#include <memory>
#include <string>
#include <vector>

class vtkCamera;
class vtkImageData;
class vtkVolume;

namespace parcvolpack
{
/// VolPack with a volume's data, transfer functions and shading, classified once.
class Renderer
{
public:
  /// Why VolPack cannot render volume (image, its property, the blend mode) seen by camera;
  /// empty when it can.
  static std::string Unsupported(
    int blendMode, vtkVolume* volume, vtkImageData* image, vtkCamera* camera);

  /// Classifies image with the volume's property (Unsupported must be empty).
  Renderer(vtkVolume* volume, vtkImageData* image);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Seconds the classification took (VolPack's preprocessing, once per transfer function).
  double ClassificationTime() const;
  /// Renders a width x height RGB image (rows bottom up, as VTK reads a window) of the
  /// volume seen by camera over black; seconds is the render's wall time.
  std::vector<unsigned char> Render(vtkCamera* camera, int width, int height, double& seconds);

private:
  struct Internals;
  std::unique_ptr<Internals> I;
};
}

#endif
