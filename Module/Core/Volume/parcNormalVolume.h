// PARC for VTK: quantized voxel normals, the fast shading model
// (ShadingModel::QuantizedNormals in parcCastParameters.h).
//
// The normal of voxel (i, j, k) is the direction of the field's central-difference
// gradient at the voxel (one-sided on the box faces), in voxel-index coordinates, stored in
// 16 bits: ZeroNormal for a zero gradient, else 1 + u + Resolution * v, where (u, v) is the
// octahedral map of the direction rounded to a Resolution x Resolution grid (at most
// MaxEncodingError radians off). A shaded sample then takes the diffuse and specular
// factors of its cell's 8 corner normals from a table made once per render (for the
// lights and one view direction) and interpolates them trilinearly at its location, as
// vtkFixedPointVolumeRayCastMapper does: a few loads instead of a gradient and a
// Blinn-Phong evaluation per sample, and a less accurate image.
#ifndef parcNormalVolume_h
#define parcNormalVolume_h

#include "parcMath.h"
#include "parcScalarField.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace parc
{

class NormalVolume
{
public:
  /// Grid cells of the octahedral map per axis.
  static constexpr int Resolution = 128;
  /// Encoded normals, ZeroNormal included.
  static constexpr std::size_t Count = 1 + static_cast<std::size_t>(Resolution) * Resolution;
  static constexpr std::uint16_t ZeroNormal = 0;
  /// The largest angle (radians) between a direction and its decoded encoding.
  static constexpr double MaxEncodingError = 0.035;

  /// The encoding of direction d (any length; ZeroNormal for 0 or a non-finite d).
  static std::uint16_t Encode(const Vec3& d);
  /// The unit vector an encoding stands for ((0, 0, 0) for ZeroNormal).
  static Vec3 Decode(std::uint16_t code);

  /// Encodes the normal of every voxel of field (in parallel; the same result for any
  /// number of threads).
  void Build(const ScalarField& field);
  /// Frees the normals.
  void Clear();
  bool IsEmpty() const { return this->Codes.empty(); }
  const int* GetDimensions() const { return this->Dims; }
  std::size_t GetMemorySize() const { return this->Codes.size() * sizeof(std::uint16_t); }

  std::uint16_t At(int i, int j, int k) const
  {
    return this->Codes[static_cast<std::size_t>(i) + this->Step[1] * j + this->Step[2] * k];
  }
  /// The codes of cell's 8 corners (corner n: x offset n & 1, y (n >> 1) & 1, z (n >> 2)
  /// & 1).
  PARC_HOT_INLINE void CellCorners(const int cell[3], std::uint16_t codes[8]) const
  {
    const std::uint16_t* c =
      this->Codes.data() + cell[0] + this->Step[1] * cell[1] + this->Step[2] * cell[2];
    const std::ptrdiff_t y = this->Step[1], z = this->Step[2];
    codes[0] = c[0];
    codes[1] = c[1];
    codes[2] = c[y];
    codes[3] = c[y + 1];
    codes[4] = c[z];
    codes[5] = c[z + 1];
    codes[6] = c[z + y];
    codes[7] = c[z + y + 1];
  }

private:
  std::vector<std::uint16_t> Codes;
  int Dims[3] = { 0, 0, 0 };
  std::ptrdiff_t Step[3] = { 1, 0, 0 };
};

} // namespace parc

#endif
