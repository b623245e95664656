// What both fragment shaders share: MeetsFace tests whether the ray through the pixel
// centre meets the face, within a rounding margin that grows as the ray grazes the face, and
// narrows the face's depth range to the depth of the hit (both from the ratios the vertex
// shader set up). Without a usable denominator the face keeps its whole range.
flat in vec2 gDepthRange;
flat in vec3 gDenominator;
flat in vec3 gDepthNumerator;
flat in vec3 gEdgeNumerator[2];
flat in vec2 gInverseEdgeLength;
flat in float gFaceScale;
flat in int gPlane;
uniform vec2 PixelToNDC;
uniform float MarginScale;
bool MeetsFace(inout vec2 range)
{
  vec3 ndc = vec3(1.0, gl_FragCoord.xy * PixelToNDC - 1.0);
  float denominator = dot(gDenominator, ndc);
  if (denominator == 0.0)
  {
    return true;
  }
  float depth = clamp(dot(gDepthNumerator, ndc) / denominator, range.x, range.y);
  float margin = MarginScale * (gFaceScale + abs(depth)) / abs(denominator);
  vec2 face = vec2(dot(gEdgeNumerator[0], ndc), dot(gEdgeNumerator[1], ndc)) / denominator;
  vec2 tolerance = margin * gInverseEdgeLength;
  if (any(lessThan(face, -tolerance)) || any(greaterThan(face, 1.0 + tolerance)))
  {
    return false;
  }
  range = vec2(max(range.x, depth - margin), min(range.y, depth + margin));
  return true;
}
