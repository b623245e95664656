// PARC for VTK examples: reading volume files, building transfer functions by name, and
// the voxelized floor of the paper's Figure 13.
#ifndef parcVolumeIO_h
#define parcVolumeIO_h

#include <string>

class vtkImageData;
class vtkVolumeProperty;

namespace parcio
{
/// Reads .vti, .mha/.mhd, .nii/.nii.gz, .nrrd/.nhdr, legacy .vtk, .slc, or a raw file
/// named like foot_256x256x256_uint8.raw (x y z, then uint8/int8/uint16/int16[le|be]/
/// uint32/int32/float32/float64). Returns false and sets error on failure.
bool ReadVolume(const std::string& path, vtkImageData* out, std::string& error);

/// Fills the property's colour and opacity functions from a preset name (ramp, mri,
/// ct-skin-bone, ct-bone, mip) scaled to range, or from a text file with lines
/// "scalar opacity red green blue" ('#' starts a comment).
bool LoadTransferFunction(const std::string& nameOrFile, const double range[2],
  vtkVolumeProperty* property, std::string& error);

/// Samples of the paper's Figure 13 floor along x, y (up) and z: 57 x 12 x 57.
constexpr int FloorSamples[3] = { 57, 12, 57 };

/// A voxelized floor slab (the paper's Figure 13 floor, 57 x 12 x 57 unsigned char samples,
/// y up) for an object with the given world bounds to stand on: centred under the object
/// in x and z and 1.2 times its larger width there, its top surface (value FloorIsoValue)
/// at the object's lowest y. The density falls linearly from 255 inside to 0 outside over
/// two samples across every face of the slab, like a volume-sampled box; the samples are
/// cubes.
void MakeFloor(const double objectBounds[6], vtkImageData* out);

/// The value of the floor's surface in MakeFloor's density.
constexpr double FloorIsoValue = 127.5;

/// An opaque, shaded isosurface at iso of one colour (rgb): the floor's, and the object's
/// in the Figure 13 scene.
void SetUpSurfaceProperty(double iso, const double rgb[3], vtkVolumeProperty* property);
}

#endif
