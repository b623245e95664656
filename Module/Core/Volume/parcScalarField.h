// PARC for VTK: a scalar volume in voxel-index space, sampled by the ray caster.
//
// Voxel (i, j, k) sits at index coordinates (i, j, k); the field is defined on the box
// [0, nx-1] x [0, ny-1] x [0, nz-1]. Positions outside the box are clamped to it.
//
// The values stay in their native type, usually in the caller's memory (no copy of 8-,
// 16- or 32-bit data): every value is converted to float when it is loaded, so a sample is
// the same float arithmetic whatever the type. The hot loops use FieldView<T>, a typed
// view obtained once per image through ScalarField::Dispatch. Non-finite floating-point
// input is the one case that is copied, with NaN replaced by the smallest finite value,
// -inf by the smallest and +inf by the largest, so that the field is finite everywhere.
#ifndef parcScalarField_h
#define parcScalarField_h

#include "parcFieldView.h"
#include "parcMath.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace parc
{

enum class ScalarType
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Float32,
  Float64
};

template <typename T>
constexpr ScalarType ScalarTypeOf()
{
  static_assert(std::is_arithmetic<T>::value, "scalar fields hold numbers");
  if (std::is_floating_point<T>::value)
  {
    return sizeof(T) == 4 ? ScalarType::Float32 : ScalarType::Float64;
  }
  switch (sizeof(T))
  {
    case 1:
      return std::is_signed<T>::value ? ScalarType::Int8 : ScalarType::UInt8;
    case 2:
      return std::is_signed<T>::value ? ScalarType::Int16 : ScalarType::UInt16;
    default:
      return std::is_signed<T>::value ? ScalarType::Int32 : ScalarType::UInt32;
  }
}

/// A field of any scalar type, referencing the caller's values or holding a copy.
class ScalarField
{
public:
  /// Refers to n = nx*ny*nz values (x fastest) without copying them, reading every
  /// `stride`-th value (for multi-component arrays); values must outlive the field's use.
  /// Floating-point values with non-finite entries are copied with those replaced (see the
  /// file comment). Returns the number replaced.
  template <typename T>
  std::size_t Wrap(const T* values, const int dims[3], int stride = 1);
  /// Like Wrap, but always keeps a copy of the values (in their type).
  template <typename T>
  std::size_t Assign(const T* values, const int dims[3], int stride = 1);

  ScalarType GetScalarType() const { return this->Type; }
  const int* GetDimensions() const { return this->Dims; }
  std::size_t GetNumberOfValues() const
  {
    return static_cast<std::size_t>(this->Dims[0]) * static_cast<std::size_t>(this->Dims[1]) *
      static_cast<std::size_t>(this->Dims[2]);
  }
  /// The finite range of the values.
  const double* GetRange() const { return this->Range; }
  /// Bytes of values the field holds itself (0 when it refers to the caller's values),
  /// not counting its bricks.
  std::size_t GetMemorySize() const { return this->Owned ? this->Owned->size() : 0; }

  /// Keeps (true) or frees (false) a copy of the values in bricks (BrickGrid), which the
  /// ray caster's lattice samples read instead of the values: the same values, so the same
  /// samples, from memory nearer each other along a ray. Wrap and Assign free it. Returns
  /// false when a copy was asked for and not made (no memory for it, or no values).
  bool SetBricked(bool bricked);
  bool IsBricked() const { return static_cast<bool>(this->Bricks); }
  /// Bytes of the copy in bricks (0 without one).
  std::size_t GetBrickedMemorySize() const
  {
    return this->Bricks ? BrickGrid(this->Dims).NumberOfValues() * this->ValueSize() : 0;
  }

  /// Calls f(FieldView<T>) for the field's value type T and returns its result.
  template <class F>
  decltype(auto) Dispatch(F&& f) const
  {
    switch (this->Type)
    {
      case ScalarType::Int8:
        return f(this->View<std::int8_t>());
      case ScalarType::UInt8:
        return f(this->View<std::uint8_t>());
      case ScalarType::Int16:
        return f(this->View<std::int16_t>());
      case ScalarType::UInt16:
        return f(this->View<std::uint16_t>());
      case ScalarType::Int32:
        return f(this->View<std::int32_t>());
      case ScalarType::UInt32:
        return f(this->View<std::uint32_t>());
      case ScalarType::Float64:
        return f(this->View<double>());
      case ScalarType::Float32:
      default:
        return f(this->View<float>());
    }
  }

  /// Values from one voxel to the next along x (the components of a voxel).
  int GetStride() const { return this->Stride; }

  // One-off access (each call dispatches on the type; loops use Dispatch).
  float GetValue(int i, int j, int k) const
  {
    return this->Dispatch([&](const auto& v) { return v.Value(i, j, k); });
  }
  void CellRange(int i, int j, int k, float& lo, float& hi) const
  {
    this->Dispatch([&](const auto& v) { v.CellRange(i, j, k, lo, hi); });
  }
  float SampleLinear(const Vec3& p) const
  {
    return this->Dispatch([&](const auto& v) { return v.SampleLinear(p); });
  }
  float SampleNearest(const Vec3& p) const
  {
    return this->Dispatch([&](const auto& v) { return v.SampleNearest(p); });
  }
  float Sample(const Vec3& p, Interpolation mode) const
  {
    return this->Dispatch([&](const auto& v) { return v.Sample(p, mode); });
  }
  Vec3 Gradient(const Vec3& p, Interpolation mode) const
  {
    return this->Dispatch([&](const auto& v) { return v.Gradient(p, mode); });
  }

  /// Bytes of a value.
  std::size_t ValueSize() const
  {
    return this->Dispatch([](const auto& v) { return sizeof(*v.Row(0, 0)); });
  }

private:
  template <typename T>
  FieldView<T> View() const
  {
    return FieldView<T>(static_cast<const T*>(this->Data), this->Dims, this->Stride,
      reinterpret_cast<const T*>(this->Bricks.get()));
  }
  template <typename T>
  void MakeBricks();
  template <typename T>
  void CopyValues(const T* values, int stride);
  template <typename T>
  std::size_t Scan();

  ScalarType Type = ScalarType::Float32;
  const void* Data = nullptr;
  int Stride = 1;
  int Dims[3] = { 0, 0, 0 };
  double Range[2] = { 0.0, 0.0 };
  /// The copy, when there is one (shared by copies of the field: it never changes).
  std::shared_ptr<std::vector<unsigned char>> Owned;
  /// The copy in bricks, when there is one (shared by copies of the field).
  std::shared_ptr<unsigned char[]> Bricks;
};

inline bool ScalarField::SetBricked(bool bricked)
{
  if (!bricked || this->GetNumberOfValues() == 0)
  {
    this->Bricks.reset();
    return !bricked;
  }
  if (!this->Bricks)
  {
    try
    {
      this->Dispatch([&](const auto& view) {
        using T = std::remove_const_t<std::remove_pointer_t<decltype(view.Row(0, 0))>>;
        this->MakeBricks<T>();
      });
    }
    catch (const std::bad_alloc&)
    {
      return false;
    }
  }
  return true;
}

template <typename T>
void ScalarField::MakeBricks()
{
  const BrickGrid grid(this->Dims);
  // Not value-initialized: every element is written below.
  std::shared_ptr<unsigned char[]> bricks(new unsigned char[grid.NumberOfValues() * sizeof(T)]);
  T* out = reinterpret_cast<T*>(bricks.get());
  const FieldView<T> view = this->View<T>();
  const std::ptrdiff_t stride = view.GetXStep();
  const int* dims = this->Dims;
  const vtkIdType count = static_cast<vtkIdType>(grid.Count[0]) * grid.Count[1] * grid.Count[2];
  vtkSMPTools::For(0, count, [&](vtkIdType b0, vtkIdType b1) {
    for (vtkIdType b = b0; b < b1; ++b)
    {
      const int brick[3] = { static_cast<int>(b % grid.Count[0]),
        static_cast<int>(b / grid.Count[0] % grid.Count[1]),
        static_cast<int>(b / grid.Count[0] / grid.Count[1]) };
      T* v = out + b * BrickGrid::Voxels;
      const auto clamped = [&](int axis, int l) {
        return std::min(std::max(BrickGrid::First(brick[axis]) + l, 0), dims[axis] - 1);
      };
      // A brick's rows inside the field along x are runs of contiguous values (one
      // component): copied whole; the others voxel by voxel, clamped.
      const int x0 = BrickGrid::First(brick[0]);
      const bool wholeRows = stride == 1 && x0 >= 0 && x0 + BrickGrid::Side <= dims[0];
      for (int lz = 0; lz < BrickGrid::Side; ++lz)
      {
        for (int ly = 0; ly < BrickGrid::Side; ++ly, v += BrickGrid::Side)
        {
          const T* row = view.Row(clamped(1, ly), clamped(2, lz));
          if (wholeRows)
          {
            std::copy_n(row + x0, BrickGrid::Side, v);
            continue;
          }
          for (int lx = 0; lx < BrickGrid::Side; ++lx)
          {
            v[lx] = row[clamped(0, lx) * stride];
          }
        }
      }
    }
  });
  this->Bricks = std::move(bricks);
}

template <typename T>
void ScalarField::CopyValues(const T* values, int stride)
{
  const std::size_t n = this->GetNumberOfValues();
  auto copy = std::make_shared<std::vector<unsigned char>>(n * sizeof(T));
  T* out = reinterpret_cast<T*>(copy->data());
  for (std::size_t i = 0; i < n; ++i)
  {
    out[i] = values[i * stride];
  }
  this->Owned = std::move(copy);
  this->Data = out;
  this->Stride = 1;
}

template <typename T>
std::size_t ScalarField::Scan()
{
  // The finite range, in parallel over chunks of values (in their own type for integers:
  // rounding to float is monotonic, so the range converted is the range of the values
  // converted), then (floating point only) the replacement of non-finite values.
  constexpr std::size_t Chunks = 64;
  struct ChunkRange
  {
    double Lo = std::numeric_limits<double>::max();
    double Hi = std::numeric_limits<double>::lowest();
    std::size_t NonFinite = 0;
  };
  const std::size_t n = this->GetNumberOfValues();
  const T* v = static_cast<const T*>(this->Data);
  const std::ptrdiff_t stride = this->Stride;
  std::vector<ChunkRange> chunks(Chunks);
  vtkSMPTools::For(0, static_cast<vtkIdType>(Chunks), [&](vtkIdType c0, vtkIdType c1) {
    for (vtkIdType c = c0; c < c1; ++c)
    {
      const std::size_t first = n * c / Chunks, last = n * (c + 1) / Chunks;
      ChunkRange& range = chunks[c];
      if (first == last)
      {
        continue;
      }
      if constexpr (std::is_integral<T>::value)
      {
        T lo = v[first * stride], hi = lo;
        const auto scan = [&](std::ptrdiff_t step) { // a constant step vectorizes
          for (std::size_t i = first; i < last; ++i)
          {
            lo = std::min(lo, v[i * step]);
            hi = std::max(hi, v[i * step]);
          }
        };
        stride == 1 ? scan(1) : scan(stride);
        range.Lo = static_cast<float>(lo);
        range.Hi = static_cast<float>(hi);
      }
      else
      {
        for (std::size_t i = first; i < last; ++i)
        {
          const double x = static_cast<double>(static_cast<float>(v[i * stride]));
          if (std::isfinite(x))
          {
            range.Lo = std::min(range.Lo, x);
            range.Hi = std::max(range.Hi, x);
          }
          else
          {
            ++range.NonFinite;
          }
        }
      }
    }
  });
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  std::size_t nonFinite = 0;
  for (const ChunkRange& range : chunks)
  {
    lo = std::min(lo, range.Lo);
    hi = std::max(hi, range.Hi);
    nonFinite += range.NonFinite;
  }
  if (lo > hi) // no finite value at all
  {
    lo = hi = 0.0;
  }
  this->Range[0] = n > 0 ? lo : 0.0;
  this->Range[1] = n > 0 ? hi : 0.0;
  if (nonFinite > 0)
  {
    if (!this->Owned)
    {
      this->CopyValues(v, this->Stride);
    }
    T* out = reinterpret_cast<T*>(this->Owned->data());
    for (std::size_t i = 0; i < n; ++i)
    {
      if (!std::isfinite(static_cast<float>(out[i])))
      {
        out[i] = static_cast<T>(static_cast<float>(out[i]) > 0.f ? hi : lo);
      }
    }
  }
  return nonFinite;
}

template <typename T>
std::size_t ScalarField::Wrap(const T* values, const int dims[3], int stride)
{
  this->Type = ScalarTypeOf<T>();
  std::copy_n(dims, 3, this->Dims);
  this->Data = values;
  this->Stride = stride;
  this->Owned.reset();
  this->Bricks.reset();
  return this->Scan<T>();
}

template <typename T>
std::size_t ScalarField::Assign(const T* values, const int dims[3], int stride)
{
  this->Type = ScalarTypeOf<T>();
  std::copy_n(dims, 3, this->Dims);
  this->CopyValues(values, stride);
  this->Bricks.reset();
  return this->Scan<T>();
}

} // namespace parc

#endif
