// PARC for VTK examples: reading volume files and building transfer functions by name.
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
}

#endif
