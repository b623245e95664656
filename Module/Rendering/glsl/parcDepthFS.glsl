// A fragment whose ray misses the face writes the blending's neutral value (faster than
// discard on llvmpipe).
uniform float Empty;
layout(location = 0) out vec4 NearFar;
void main()
{
  vec2 range = gDepthRange;
  NearFar = MeetsFace(range) ? vec4(range.x, -range.y, 0.0, 0.0) : vec4(Empty, Empty, 0.0, 0.0);
}
