#include "parcMath.h"

#include <utility>

namespace parc
{

Matrix4 Multiply(const Matrix4& a, const Matrix4& b)
{
  Matrix4 r;
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      double sum = 0.0;
      for (int k = 0; k < 4; ++k)
      {
        sum += a(i, k) * b(k, j);
      }
      r(i, j) = sum;
    }
  }
  return r;
}

bool Invert(const Matrix4& m, Matrix4& out)
{
  // Gauss-Jordan elimination with partial pivoting on [m | I].
  double a[4][8];
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      a[i][j] = m(i, j);
      a[i][j + 4] = (i == j) ? 1.0 : 0.0;
    }
  }
  for (int col = 0; col < 4; ++col)
  {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
    {
      if (std::fabs(a[r][col]) > std::fabs(a[pivot][col]))
      {
        pivot = r;
      }
    }
    if (a[pivot][col] == 0.0 || !std::isfinite(a[pivot][col]))
    {
      return false;
    }
    if (pivot != col)
    {
      for (int j = 0; j < 8; ++j)
      {
        std::swap(a[pivot][j], a[col][j]);
      }
    }
    const double inv = 1.0 / a[col][col];
    for (int j = 0; j < 8; ++j)
    {
      a[col][j] *= inv;
    }
    for (int r = 0; r < 4; ++r)
    {
      if (r != col && a[r][col] != 0.0)
      {
        const double f = a[r][col];
        for (int j = 0; j < 8; ++j)
        {
          a[r][j] -= f * a[col][j];
        }
      }
    }
  }
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      out(i, j) = a[i][j + 4];
    }
  }
  return true;
}

} // namespace parc
