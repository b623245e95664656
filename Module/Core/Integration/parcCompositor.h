// PARC for VTK: the one front-to-back compositor of the caster. A ray's contributions
// (samples, isosurface crossings, whole-ray results of other volumes) are RayEvents; the
// compositor adds them with the "over" rule in the order they come, which is ray order.
#ifndef parcCompositor_h
#define parcCompositor_h

#include <algorithm>

namespace parc
{

/// What one volume contributes at one point of a ray (see the file comment).
struct RayEvent
{
  double T;     ///< ray parameter
  float Rgb[3]; ///< colour; premultiplied by Alpha when Premultiplied
  float Alpha;  ///< opacity (corrected for the sample distance)
  /// Rgb is premultiplied: a whole-ray result, or a sample of independent components
  /// (parcRayCaster.h), rather than one sample's colour and opacity.
  bool Premultiplied;
};

/// Front-to-back "over" of events, in the order they are added.
struct EventCompositor
{
  float Rgb[3] = { 0.f, 0.f, 0.f };
  float Alpha = 0.f;

  /// Adds a sample of colour rgb and opacity a behind what was added before.
  void AddSample(const float rgb[3], float a)
  {
    const float w = Weight(this->Alpha, a);
    for (int c = 0; c < 3; ++c)
    {
      this->Rgb[c] += w * rgb[c];
    }
    this->Alpha += w;
  }
  /// The weight of a sample of opacity a behind accumulated opacity alpha: its colour's
  /// share of the result, and what it adds to alpha.
  static float Weight(float alpha, float a) { return (1.f - alpha) * a; }
  /// Adds e behind what was added before.
  void Add(const RayEvent& e)
  {
    if (!e.Premultiplied)
    {
      this->AddSample(e.Rgb, e.Alpha);
      return;
    }
    this->AddPremultiplied(e.Rgb, e.Alpha);
  }
  /// Adds premultiplied colour rgb and opacity a behind what was added before.
  void AddPremultiplied(const float rgb[3], float a)
  {
    const float transparency = 1.f - this->Alpha;
    for (int c = 0; c < 3; ++c)
    {
      this->Rgb[c] += transparency * rgb[c];
    }
    this->Alpha += transparency * a;
  }
  void Finish(float rgba[4]) const
  {
    std::copy_n(this->Rgb, 3, rgba);
    rgba[3] = this->Alpha;
  }
};

} // namespace parc

#endif
