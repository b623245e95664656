// PARC for VTK: a scalar volume in voxel-index space, sampled by the ray caster.
//
// Values are kept as float (converted once per data change from any scalar type). Voxel
// (i, j, k) sits at index coordinates (i, j, k); the field is defined on the box
// [0, nx-1] x [0, ny-1] x [0, nz-1]. Positions outside the box are clamped to it.
// Non-finite input values are replaced when converted (see Assign) so that the field is
// finite everywhere.
#ifndef parcScalarField_h
#define parcScalarField_h

#include "parcMath.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace parc
{

enum class Interpolation
{
  Nearest,
  Linear
};

class ScalarField
{
public:
  /// Copies n = nx*ny*nz values (x fastest) converting them to float, reading every
  /// `stride`-th value (for multi-component arrays). NaN becomes the smallest finite
  /// value, -inf the smallest and +inf the largest. Returns the number replaced.
  template <typename T>
  std::size_t Assign(const T* values, const int dims[3], int stride = 1);

  const int* GetDimensions() const { return this->Dims; }
  std::size_t GetNumberOfValues() const { return this->Values.size(); }
  const float* GetValues() const { return this->Values.data(); }
  float GetValue(int i, int j, int k) const
  {
    return this->Values[static_cast<std::size_t>(i) +
      static_cast<std::size_t>(this->Dims[0]) *
        (static_cast<std::size_t>(j) + static_cast<std::size_t>(this->Dims[1]) * k)];
  }
  /// The finite range of the values.
  const double* GetRange() const { return this->Range; }

  /// Trilinear interpolation at index coordinates p (clamped to the box).
  float SampleLinear(const Vec3& p) const;
  /// The value of the nearest voxel to p (ties round up; clamped to the box).
  float SampleNearest(const Vec3& p) const;
  float Sample(const Vec3& p, Interpolation mode) const
  {
    return mode == Interpolation::Linear ? this->SampleLinear(p) : this->SampleNearest(p);
  }
  /// Central-difference gradient of the interpolated field at p, in scalar units per voxel
  /// index (one-sided at the box faces).
  Vec3 Gradient(const Vec3& p, Interpolation mode) const;

private:
  void ReplaceNonFinite(std::size_t& replaced);
  /// Trilinear interpolation in cell (i, j, k) at fractions (fx, fy, fz) of its edges.
  float Trilinear(const int cell[3], const float fraction[3]) const;
  Vec3 GradientLinear(const Vec3& p) const;

  int Dims[3] = { 0, 0, 0 };
  std::vector<float> Values;
  double Range[2] = { 0.0, 0.0 };
};

template <typename T>
std::size_t ScalarField::Assign(const T* values, const int dims[3], int stride)
{
  for (int a = 0; a < 3; ++a)
  {
    this->Dims[a] = dims[a];
  }
  const std::size_t n =
    static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) * dims[2];
  this->Values.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    this->Values[i] = static_cast<float>(values[i * stride]);
  }
  std::size_t replaced = 0;
  this->ReplaceNonFinite(replaced);
  return replaced;
}

} // namespace parc

#endif
