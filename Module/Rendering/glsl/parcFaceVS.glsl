// The vertex shader of both PARC passes (embedded into vtkPARCRasterizer at build time).
// Four vertices a quad, each with the quad's corner, its two edges and its plane
// (voxel-index coordinates); vertex gl_VertexID & 3 becomes a corner of the quad's dilated
// screen projection (TightQuad) or, when that is no smaller, of its dilated bounding box
// (two triangles: corners 0 1 2 and 2 1 3), each vertex computing the same flat outputs.
// The quad is first clipped to the part in front of MinDepth. The shader also sets up the
// ratios the fragment shaders evaluate (parcFaceFS.glsl).
layout(location = 0) in vec3 Corner;
layout(location = 1) in vec3 Edge1;
layout(location = 2) in vec3 Edge3;
layout(location = 3) in int Plane;
uniform mat4 IndexToRelative;
uniform mat4 RelativeToClip;
uniform vec3 ViewDirection;
uniform float MinDepth;
uniform vec2 Dilation;
uniform vec3 SkipNormal;
uniform float FrameScale;
uniform vec3 RayBase[3];
uniform vec3 RayDirection[3];
flat out vec2 gDepthRange;
flat out int gPlane;
flat out vec3 gDenominator;
flat out vec3 gDepthNumerator;
flat out vec3 gEdgeNumerator[2];
flat out vec2 gInverseEdgeLength;
flat out float gFaceScale;
// The affine coefficients of (dot(b, q) - c) d + m dot(u, q) for affine d and m.
vec3 Numerator(vec3 q, float c, vec3 d, vec3 m)
{
  vec3 l = vec3(dot(RayBase[0], q) - c, dot(RayBase[1], q), dot(RayBase[2], q));
  vec3 k = vec3(dot(RayDirection[0], q), dot(RayDirection[1], q), dot(RayDirection[2], q));
  return vec3(l.x * d.x + m.x * k.x, l.x * d.y + l.y * d.x + m.x * k.y + m.y * k.x,
    l.x * d.z + l.z * d.x + m.x * k.z + m.z * k.x);
}
// The quad's projection (no corner in front of MinDepth clipped: a convex quadrilateral),
// each edge moved out by the dilation box's extent along the edge's normal: it holds every
// point within the dilation of the projection, as the dilated bounding box does, often in
// far less area (fewer fragments). False, q unset, when it is not smaller than boxArea, has
// a corner beyond the box's margin (NDC -2 to 2) or is degenerate.
bool TightQuad(float depth[4], vec4 clip[4], float boxArea, out vec2 q[4])
{
  vec2 p[4];
  float twiceArea = 0.0;
  for (int i = 0; i < 4; ++i)
  {
    if (depth[i] < MinDepth || clip[i].w <= 0.0)
    {
      return false;
    }
    p[i] = clip[i].xy / clip[i].w;
  }
  for (int i = 0; i < 4; ++i)
  {
    vec2 a = p[i];
    vec2 b = p[(i + 1) % 4];
    twiceArea += a.x * b.y - a.y * b.x;
  }
  if (abs(twiceArea) < 1.0e-12)
  {
    return false;
  }
  // Edge i runs from p[i] to p[i + 1]; its outward unit normal n and offset c: the moved
  // edge is dot(n, x) = c.
  float orientation = sign(twiceArea);
  vec2 n[4];
  float c[4];
  for (int i = 0; i < 4; ++i)
  {
    vec2 e = p[(i + 1) % 4] - p[i];
    float len = length(e);
    if (len == 0.0)
    {
      return false;
    }
    n[i] = orientation * vec2(e.y, -e.x) / len;
    c[i] = dot(n[i], p[i]) + Dilation.x * abs(n[i].x) + Dilation.y * abs(n[i].y);
  }
  // Corner i where the moved edges i - 1 and i meet.
  float area = 0.0;
  for (int i = 0; i < 4; ++i)
  {
    vec2 a = n[(i + 3) % 4];
    vec2 b = n[i];
    float ca = c[(i + 3) % 4];
    float det = a.x * b.y - a.y * b.x;
    if (abs(det) < 1.0e-3)
    {
      return false; // nearly parallel neighbours: a far spike
    }
    q[i] = vec2(ca * b.y - a.y * c[i], a.x * c[i] - ca * b.x) / det;
    if (any(greaterThan(abs(q[i]), vec2(2.0))))
    {
      return false;
    }
  }
  for (int i = 0; i < 4; ++i)
  {
    area += q[i].x * q[(i + 1) % 4].y - q[i].y * q[(i + 1) % 4].x;
  }
  return 0.5 * abs(area) < boxArea;
}

void main()
{
  vec3 corners[4] = vec3[4](Corner, Corner + Edge1, Corner + Edge1 + Edge3, Corner + Edge3);
  vec3 relative[4];
  vec4 clip[4];
  float depth[4];
  for (int i = 0; i < 4; ++i)
  {
    relative[i] = (IndexToRelative * vec4(corners[i], 1.0)).xyz;
    clip[i] = RelativeToClip * vec4(relative[i], 1.0);
    depth[i] = dot(relative[i], ViewDirection);
  }
  vec2 lo = vec2(3.0e38);
  vec2 hi = vec2(-3.0e38);
  float zlo = 3.0e38;
  float zhi = -3.0e38;
  for (int i = 0; i < 4; ++i)
  {
    int j = (i + 1) % 4;
    bool inI = depth[i] >= MinDepth;
    bool inJ = depth[j] >= MinDepth;
    if (inI)
    {
      vec2 ndc = clip[i].xy / clip[i].w;
      lo = min(lo, ndc);
      hi = max(hi, ndc);
      zlo = min(zlo, depth[i]);
      zhi = max(zhi, depth[i]);
    }
    if (inI != inJ)
    {
      vec4 c = mix(clip[i], clip[j], (MinDepth - depth[i]) / (depth[j] - depth[i]));
      vec2 ndc = c.xy / c.w;
      lo = min(lo, ndc);
      hi = max(hi, ndc);
      zlo = min(zlo, MinDepth);
      zhi = max(zhi, MinDepth);
    }
  }
  gPlane = Plane;
  gDepthRange = vec2(zlo, zhi);
  // Nothing in front, or a face the rays cannot enter through (its outward normal, the
  // edges' cross product, along SkipNormal): a degenerate strip.
  if (zlo > zhi || dot(cross(Edge1, Edge3), SkipNormal) > 0.0)
  {
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  // Beyond the viewport (NDC -1 to 1) the box only makes the primitive huge: clamped to a
  // margin around it, so the rasterizer never clips far-away coordinates.
  lo = max(lo - Dilation, vec2(-2.0));
  hi = min(hi + Dilation, vec2(2.0));
  int box = gl_VertexID & 3;
  vec2 q[4];
  if (TightQuad(depth, clip, (hi.x - lo.x) * (hi.y - lo.y), q))
  {
    // The strip's corners 0 1 2 3 are the quad's 0 1 3 2.
    gl_Position = vec4(q[box == 2 ? 3 : (box == 3 ? 2 : box)], 0.0, 1.0);
  }
  else
  {
    gl_Position = vec4((box & 1) != 0 ? hi.x : lo.x, (box & 2) != 0 ? hi.y : lo.y, 0.0, 1.0);
  }
  // The face's plane dot(n, x) = w (eye-relative world coordinates). The ray through NDC
  // (x, y) starts at b = RayBase . (1, x, y) and runs along u = RayDirection . (1, x, y); it
  // meets the plane at p = b + u (w - dot(n, b)) / dot(n, u). For a vector q and offset c,
  // (dot(p, q) - c) dot(n, u) = (dot(b, q) - c) dot(n, u) + (w - dot(n, b)) dot(u, q) is
  // affine in (x, y) because b = 0 (perspective) or u is constant (parallel): the depth
  // (q = view direction) and the face coordinates along both edges are ratios of affine
  // functions with the common denominator dot(n, u). gFaceScale bounds the magnitudes
  // they are computed from.
  vec3 e1 = relative[1] - relative[0];
  vec3 e3 = relative[3] - relative[0];
  vec3 n = normalize(cross(e1, e3));
  float w = dot(n, relative[0]);
  vec3 m = vec3(w - dot(n, RayBase[0]), -dot(n, RayBase[1]), -dot(n, RayBase[2]));
  vec3 d = vec3(dot(n, RayDirection[0]), dot(n, RayDirection[1]), dot(n, RayDirection[2]));
  gDenominator = d;
  gDepthNumerator = Numerator(ViewDirection, 0.0, d, m);
  // The face coordinates of a point p of the plane are dot(p - relative[0], q) for the dual
  // basis q1, q3 of the edges (dot(q1, e1) = dot(q3, e3) = 1, dot(q1, e3) = dot(q3, e1) = 0):
  // a quad of a sheared volume is a parallelogram whose edges are not orthogonal. A point
  // at distance r from p changes them by at most r |q|.
  vec3 normal = cross(e1, e3);
  vec3 q1 = cross(e3, normal) / dot(normal, normal);
  vec3 q3 = cross(normal, e1) / dot(normal, normal);
  gEdgeNumerator[0] = Numerator(q1, dot(relative[0], q1), d, m);
  gEdgeNumerator[1] = Numerator(q3, dot(relative[0], q3), d, m);
  gInverseEdgeLength = vec2(length(q1), length(q3));
  gFaceScale = length(relative[0]) + FrameScale + length(e1) + length(e3) +
    length(RayBase[0]) + length(RayBase[1]) + length(RayBase[2]);
}
