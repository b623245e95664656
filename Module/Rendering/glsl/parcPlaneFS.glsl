// The face's plane bit when its ray meets the face and the plane is in this pass; zero
// (neutral for OR) otherwise.
uniform int PlaneBase;
layout(location = 0) out uvec4 Bits0;
layout(location = 1) out uvec4 Bits1;
layout(location = 2) out uvec4 Bits2;
layout(location = 3) out uvec4 Bits3;
layout(location = 4) out uvec4 Bits4;
layout(location = 5) out uvec4 Bits5;
layout(location = 6) out uvec4 Bits6;
layout(location = 7) out uvec4 Bits7;
void main()
{
  int p = gPlane - PlaneBase;
  vec2 range = gDepthRange;
  uvec4 word = uvec4(0u);
  if (p >= 0 && p < 1024 && MeetsFace(range))
  {
    word[(p >> 5) & 3] = 1u << uint(p & 31);
  }
  int a = p >> 7;
  Bits0 = a == 0 ? word : uvec4(0u);
  Bits1 = a == 1 ? word : uvec4(0u);
  Bits2 = a == 2 ? word : uvec4(0u);
  Bits3 = a == 3 ? word : uvec4(0u);
  Bits4 = a == 4 ? word : uvec4(0u);
  Bits5 = a == 5 ? word : uvec4(0u);
  Bits6 = a == 6 ? word : uvec4(0u);
  Bits7 = a == 7 ? word : uvec4(0u);
}
