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

/// Front-to-back "over" of events, in the order they are added. Besides the opacity it
/// keeps the transparency left behind the events: a sample's weight is that transparency
/// times its opacity, and the chain from sample to sample is one multiplication (the
/// transparency) and one addition (the opacity), independent of each other. Nothing is
/// left behind an opaque sample: the opacity is then exactly 1.
struct EventCompositor
{
  float Rgb[3] = { 0.f, 0.f, 0.f };
  float Alpha = 0.f;
  float Transparency = 1.f;

  /// Whether the opacity accumulated so far is below termination (the ray goes on).
  bool Below(double termination) const { return this->Alpha < termination; }
  /// Adds a sample of colour rgb and opacity a behind what was added before.
  void AddSample(const float rgb[3], float a)
  {
    const float w = this->Absorb(a);
    for (int c = 0; c < 3; ++c)
    {
      this->Rgb[c] += w * rgb[c];
    }
  }
  /// Puts opacity a behind what was added before (transparency and opacity, not the
  /// colour); returns its weight, the share of its colour in the result.
  float Absorb(float a)
  {
    const float w = this->Transparency * a;
    this->Transparency *= 1.f - a;
    this->Alpha = this->Transparency > 0.f ? this->Alpha + w : 1.f;
    return w;
  }
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
    for (int c = 0; c < 3; ++c)
    {
      this->Rgb[c] += this->Transparency * rgb[c];
    }
    this->Absorb(a);
  }
  void Finish(float rgba[4]) const
  {
    std::copy_n(this->Rgb, 3, rgba);
    rgba[3] = this->Alpha;
  }
};

} // namespace parc

#endif
