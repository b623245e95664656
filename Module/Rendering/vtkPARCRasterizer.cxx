#include "vtkPARCRasterizer.h"

#include "parcBufferSources.h"
#include "parcDepthFS.h"
#include "parcDriverMemory.h"
#include "parcFaceFS.h"
#include "parcFaceVS.h"
#include "parcPassGLState.h"
#include "parcPlaneFS.h"
#include "parcStatistics.h"
#include "parcVTKConversion.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkWeakPointer.h"
#include "vtk_glew.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace
{
constexpr int PlanesPerAttachment = 128; ///< one GL_RGBA32UI texel: 4 x 32 bits
constexpr int MaxAttachments = 8;
constexpr int PlanesPerPass = PlanesPerAttachment * MaxAttachments;
/// An unsigned integer colour attachment of the plane pass: its internal format, the
/// format glReadPixels reads it as and its 32-bit words per texel.
struct TexelFormat
{
  GLenum Internal;
  GLenum Format;
  int Words;
};
constexpr TexelFormat WideTexel{ GL_RGBA32UI, GL_RGBA_INTEGER, 4 };
/// The attachment of fewest channels that holds words 32-bit words (at most 4; three
/// channels are not renderable everywhere).
TexelFormat NarrowestTexel(int words)
{
  return words == 1 ? TexelFormat{ GL_R32UI, GL_RED_INTEGER, 1 }
    : words == 2    ? TexelFormat{ GL_RG32UI, GL_RG_INTEGER, 2 }
                    : WideTexel;
}
/// How far a face's rasterized area reaches beyond its projection (its bounding box, or its
/// edges along their normals), more than half a pixel.
constexpr double DilationPixels = 0.75;
constexpr double NearClipFraction = 0.5; ///< perspective: clip at this fraction of near
/// The rounding margin of a fragment's hit depth and face coordinates, relative to the
/// magnitudes that enter them (about 800 float ulps, far above the handful of roundings in
/// the shaders; the rasterizer test fails without it).
constexpr float FaceDepthMargin = 1.0e-4f;

/// A compiled and linked program of the vertex shader and parcFaceFS + fragment.
GLuint BuildProgram(const char* fragment, std::string& error)
{
  const char* version = "#version 330 core\n";
  const GLenum types[2] = { GL_VERTEX_SHADER, GL_FRAGMENT_SHADER };
  const std::array<const char*, 3> sources[2] = { { version, parcFaceVS, "" },
    { version, parcFaceFS, fragment } };
  const GLuint program = glCreateProgram();
  GLuint shaders[2];
  for (int s = 0; s < 2; ++s)
  {
    shaders[s] = glCreateShader(types[s]);
    glShaderSource(shaders[s], 3, sources[s].data(), nullptr);
    glCompileShader(shaders[s]);
    GLint ok = 0;
    glGetShaderiv(shaders[s], GL_COMPILE_STATUS, &ok);
    if (!ok)
    {
      char log[1024] = { 0 };
      glGetShaderInfoLog(shaders[s], sizeof(log), nullptr, log);
      error = std::string("a PARC shader does not compile: ") + log;
    }
    glAttachShader(program, shaders[s]);
  }
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  for (GLuint shader : shaders)
  {
    glDetachShader(program, shader);
    glDeleteShader(shader);
  }
  if (!linked)
  {
    if (error.empty())
    {
      char log[1024] = { 0 };
      glGetProgramInfoLog(program, sizeof(log), nullptr, log);
      error = std::string("the PARC program does not link: ") + log;
    }
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

void SetVector(GLuint program, const char* name, const parc::Vec3& v)
{
  glUniform3f(glGetUniformLocation(program, name), static_cast<float>(v.X),
    static_cast<float>(v.Y), static_cast<float>(v.Z));
}

void SetVectors(GLuint program, const char* name, const parc::Vec3 (&v)[3])
{
  float values[9];
  for (int i = 0; i < 3; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      values[3 * i + c] = static_cast<float>(v[i][c]);
    }
  }
  glUniform3fv(glGetUniformLocation(program, name), 3, values);
}

/// Row-major double matrix -> column-major float uniform.
void SetMatrix(GLuint program, const char* name, const parc::Matrix4& m)
{
  float v[16];
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      v[4 * c + r] = static_cast<float>(m(r, c));
    }
  }
  glUniformMatrix4fv(glGetUniformLocation(program, name), 1, GL_FALSE, v);
}

/// A model on the GPU.
struct GPUModel
{
  GLuint VertexArray = 0;
  GLuint Positions = 0;
  GLuint Planes = 0;
  GLuint Indices = 0;
  GLsizei Count = 0; ///< quads
  std::size_t IndexedQuads = 0; ///< the quads the index buffer holds indices for
  std::uint64_t Version = ~std::uint64_t(0);
  std::size_t Bytes = 0; ///< buffer storage
  double LargestCorner = 0.0; ///< the largest |vertex| (voxel-index coordinates)

  void Release()
  {
    if (this->VertexArray)
    {
      glDeleteVertexArrays(1, &this->VertexArray);
      glDeleteBuffers(1, &this->Positions);
      glDeleteBuffers(1, &this->Planes);
      glDeleteBuffers(1, &this->Indices);
    }
    *this = GPUModel();
  }
};

/// An offscreen framebuffer with its colour renderbuffers (one per pass, so that passes
/// alternating in one frame do not reallocate each other's storage).
struct RenderTarget
{
  GLuint Framebuffer = 0;
  std::vector<GLuint> Renderbuffers;
  GLenum Format = 0;
  int Size[2] = { 0, 0 };

  /// Binds the framebuffer (through VTK's state cache) with attachments renderbuffers of
  /// format, (re)allocating storage when anything changed; false with a message when it is
  /// incomplete.
  bool Bind(vtkOpenGLState* state, GLenum format, int attachments, int width, int height,
    std::string& error);
  /// Whether Bind allocates storage for these arguments.
  bool Allocates(GLenum format, int attachments, int width, int height) const
  {
    return format != this->Format || width != this->Size[0] || height != this->Size[1] ||
      static_cast<int>(this->Renderbuffers.size()) != attachments;
  }
  /// Bytes of renderbuffer storage.
  std::size_t GetMemorySize() const
  {
    const std::size_t texel = this->Format == GL_R32UI ? 4
      : this->Format == GL_RG32F || this->Format == GL_RG32UI ? 8
                                                              : 16; // RGBA32UI
    return this->Renderbuffers.size() * texel * static_cast<std::size_t>(this->Size[0]) *
      static_cast<std::size_t>(this->Size[1]);
  }
  void Release()
  {
    this->Detach();
    if (this->Framebuffer)
    {
      glDeleteFramebuffers(1, &this->Framebuffer);
    }
    *this = RenderTarget();
  }

private:
  void Detach()
  {
    if (!this->Renderbuffers.empty())
    {
      glDeleteRenderbuffers(
        static_cast<GLsizei>(this->Renderbuffers.size()), this->Renderbuffers.data());
    }
    this->Renderbuffers.clear();
  }
};

bool RenderTarget::Bind(vtkOpenGLState* state, GLenum format, int attachments, int width,
  int height, std::string& error)
{
  if (!this->Framebuffer)
  {
    glGenFramebuffers(1, &this->Framebuffer);
  }
  state->vtkglBindFramebuffer(GL_FRAMEBUFFER, this->Framebuffer);
  if (this->Allocates(format, attachments, width, height))
  {
    for (int a = 0; a < static_cast<int>(this->Renderbuffers.size()); ++a)
    {
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + a, GL_RENDERBUFFER, 0);
    }
    this->Detach();
    this->Renderbuffers.assign(attachments, 0);
    glGenRenderbuffers(attachments, this->Renderbuffers.data());
    for (int a = 0; a < attachments; ++a)
    {
      glBindRenderbuffer(GL_RENDERBUFFER, this->Renderbuffers[a]);
      glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
      glFramebufferRenderbuffer(
        GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + a, GL_RENDERBUFFER, this->Renderbuffers[a]);
    }
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    this->Format = format;
    this->Size[0] = width;
    this->Size[1] = height;
  }
  std::array<unsigned int, MaxAttachments> buffers;
  for (int a = 0; a < attachments; ++a)
  {
    buffers[a] = GL_COLOR_ATTACHMENT0 + a;
  }
  state->vtkglDrawBuffers(static_cast<unsigned int>(attachments), buffers.data());
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
  {
    error = "the PARC framebuffer is incomplete (status " + std::to_string(status) + ")";
    this->Size[0] = this->Size[1] = 0; // rebuild next time
    return false;
  }
  return true;
}
}

//------------------------------------------------------------------------------
class vtkPARCRasterizer::vtkInternals
{
public:
  /// Weak: the window may be destroyed first; its GL objects then went with its context.
  vtkWeakPointer<vtkOpenGLRenderWindow> Context;
  GLuint DepthProgram = 0;
  GLuint PlaneProgram = 0;
  static constexpr int Passes = 2;
  GPUModel Models[Passes];      ///< by Pass
  RenderTarget Targets[Passes]; ///< by Pass
  std::vector<std::uint32_t> Texels; ///< read-back of one plane attachment
  /// What the GL implementation holds for this rasterizer's calls: measured from the
  /// first set-up of a pass (programs built, a model uploaded, a render target allocated:
  /// SettingUp) to its end, and over the releases. A warm pass is not measured: the
  /// driver frees what it allocates there (a scene's bins) outside it, at the window's
  /// next flush; and measuring the heap walks the allocator's free lists.
  parc::vtk::DriverMemory Driver;
  std::optional<parc::vtk::DriverMemory::Scope> SetUpScope; ///< of the current pass
  void SettingUp()
  {
    if (!this->SetUpScope)
    {
      this->SetUpScope.emplace(this->Driver);
    }
  }
  /// Bytes of the models and render targets GL holds for the passes.
  std::size_t GetObjectsMemorySize() const;
  /// Seconds spent so far making the context current, compiling the programs, uploading
  /// models and binding (allocating) render targets.
  double SetUpTime = 0.0;

  bool Prepare(vtkRenderWindow* window, std::string& error);
  /// One pass (RunPass), its GL memory measured when it sets up.
  template <class Body>
  bool Run(vtkRenderWindow* window, const char* pass, std::string& error, Body&& body)
  {
    const bool ok = this->RunPass(window, pass, error, body);
    this->SetUpScope.reset(); // adds what the set-up allocated
    return ok;
  }
  /// One pass: makes the context current (building the programs the first time), saves
  /// the GL state for the duration, sets the state both passes share, runs body(state)
  /// and reports a GL error as a failure of the named pass.
  template <class Body>
  bool RunPass(vtkRenderWindow* window, const char* pass, std::string& error, Body&& body)
  {
    error.clear();
    const auto start = std::chrono::steady_clock::now();
    const bool prepared = this->Prepare(window, error);
    this->SetUpTime += parc::SecondsSince(start);
    if (!prepared)
    {
      return false;
    }
    vtkOpenGLState* state = this->Context->GetState();
    // The pass starts from the state the context really has: VTK's cache of it can be
    // wrong (a window's first frame after another window's showed blending on while it
    // was off). An error other code left pending is not this pass's failure.
    state->Reset();
    while (glGetError() != GL_NO_ERROR)
    {
    }
    parc::vtk::ScopedPassState saved(state);
    parc::vtk::SetCommonPassState(state);
    if (!body(state))
    {
      return false;
    }
    if (glGetError() != GL_NO_ERROR)
    {
      error = std::string("an OpenGL error in the ") + pass + " pass";
      return false;
    }
    return true;
  }
  void Upload(GPUModel& gpu, const parc::PolygonModel& model, std::uint64_t version);
  /// The GPU copy of pass's model, uploaded when its version changed.
  const GPUModel& Use(Pass pass, const parc::PolygonModel& model, std::uint64_t version,
    std::uint64_t& uploads)
  {
    GPUModel& gpu = this->Models[static_cast<int>(pass)];
    if (gpu.Version != version)
    {
      this->SettingUp();
      const auto start = std::chrono::steady_clock::now();
      // No glFinish after it: llvmpipe copies the data in glBufferData already, and a
      // finish here made the next draw ~0.5 ms slower.
      this->Upload(gpu, model, version);
      this->SetUpTime += parc::SecondsSince(start);
      ++uploads;
    }
    return gpu;
  }
  /// The render target of pass bound, its time counted as set-up.
  bool BindTarget(
    Pass pass, GLenum format, int attachments, int width, int height, std::string& error)
  {
    const auto start = std::chrono::steady_clock::now();
    RenderTarget& target = this->Targets[static_cast<int>(pass)];
    if (target.Allocates(format, attachments, width, height))
    {
      this->SettingUp();
    }
    const bool bound =
      target.Bind(this->Context->GetState(), format, attachments, width, height, error);
    this->SetUpTime += parc::SecondsSince(start);
    return bound;
  }
  /// Draws the model's quads, except those whose outward normal (voxel-index coordinates)
  /// points along skipNormal.
  void Draw(GLuint program, const GPUModel& gpu, const parc::Matrix4& indexToWorld,
    const vtkPARCRasterizer::View& view, const parc::Vec3& skipNormal);
  void Release();
};

bool vtkPARCRasterizer::vtkInternals::Prepare(vtkRenderWindow* window, std::string& error)
{
  auto* context = vtkOpenGLRenderWindow::SafeDownCast(window);
  if (!context || !context->GetState())
  {
    error = "the render window has no OpenGL context";
    return false;
  }
  if (context != this->Context)
  {
    this->Release();
    this->Context = context;
  }
  context->MakeCurrent();
  if (!this->DepthProgram)
  {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 33)
    {
      error = "the OpenGL context is older than 3.3";
      return false;
    }
    this->SettingUp();
    this->DepthProgram = BuildProgram(parcDepthFS, error);
    this->PlaneProgram = this->DepthProgram ? BuildProgram(parcPlaneFS, error) : 0;
    if (!this->PlaneProgram)
    {
      return false;
    }
  }
  return true;
}

void vtkPARCRasterizer::vtkInternals::Upload(
  GPUModel& gpu, const parc::PolygonModel& model, std::uint64_t version)
{
  if (!gpu.VertexArray)
  {
    glGenVertexArrays(1, &gpu.VertexArray);
    glGenBuffers(1, &gpu.Positions);
    glGenBuffers(1, &gpu.Planes);
    glGenBuffers(1, &gpu.Indices);
  }
  // Per quad: its first corner and the edges to its second and fourth corners (the model's
  // quads are parallelograms), then its plane (colour models only: without planes the
  // attribute keeps its default 0); each four times, once per vertex of the quad's two
  // triangles (one indexed draw of every quad: llvmpipe shades the vertices of one draw in
  // batches, where an instance a quad would be a draw of four vertices).
  const std::size_t quads = model.GetNumberOfQuads();
  constexpr std::size_t floatsPerVertex = 9;
  std::vector<float> geometry(4 * floatsPerVertex * quads);
  std::vector<GLint> planes(model.Planes.empty() ? 0 : 4 * quads, 0);
  float* out = geometry.data();
  double largest = 0.0; // squared
  for (std::size_t q = 0; q < quads; ++q)
  {
    const parc::Vec3* v = model.Vertices.data() + 4 * q;
    for (int corner = 0; corner < 4; ++corner)
    {
      largest = std::max(largest, parc::Dot(v[corner], v[corner]));
    }
    const parc::Vec3 e1 = v[1] - v[0], e3 = v[3] - v[0];
    const float vertex[floatsPerVertex] = { static_cast<float>(v[0].X),
      static_cast<float>(v[0].Y), static_cast<float>(v[0].Z), static_cast<float>(e1.X),
      static_cast<float>(e1.Y), static_cast<float>(e1.Z), static_cast<float>(e3.X),
      static_cast<float>(e3.Y), static_cast<float>(e3.Z) };
    for (int corner = 0; corner < 4; ++corner, out += floatsPerVertex)
    {
      std::copy_n(vertex, floatsPerVertex, out);
    }
    if (q < model.Planes.size() && !planes.empty())
    {
      std::fill_n(planes.data() + 4 * q, 4, model.Planes[q]);
    }
  }
  gpu.LargestCorner = std::sqrt(largest);
  glBindVertexArray(gpu.VertexArray);
  glBindBuffer(GL_ARRAY_BUFFER, gpu.Positions);
  glBufferData(GL_ARRAY_BUFFER, geometry.size() * sizeof(float), geometry.data(), GL_STATIC_DRAW);
  for (GLuint a = 0; a < 3; ++a)
  {
    glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 9 * sizeof(float),
      reinterpret_cast<const void*>(3 * a * sizeof(float)));
    glEnableVertexAttribArray(a);
  }
  if (planes.empty())
  {
    glDisableVertexAttribArray(3);
  }
  else
  {
    glBindBuffer(GL_ARRAY_BUFFER, gpu.Planes);
    glBufferData(GL_ARRAY_BUFFER, planes.size() * sizeof(GLint), planes.data(), GL_STATIC_DRAW);
    glVertexAttribIPointer(3, 1, GL_INT, 0, nullptr);
    glEnableVertexAttribArray(3);
  }
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.Indices); // kept in the vertex array's state
  if (quads > gpu.IndexedQuads)
  {
    // The same indices for every model: made again only for more quads than ever before.
    std::vector<GLuint> indices;
    indices.reserve(6 * quads);
    for (std::size_t q = 0; q < quads; ++q)
    {
      // The box corners 0 to 3 (gl_VertexID & 3) as the triangles of a strip.
      const auto first = static_cast<GLuint>(4 * q);
      indices.insert(
        indices.end(), { first, first + 1, first + 2, first + 2, first + 1, first + 3 });
    }
    glBufferData(
      GL_ELEMENT_ARRAY_BUFFER, indices.size() * sizeof(GLuint), indices.data(), GL_STATIC_DRAW);
    gpu.IndexedQuads = quads;
  }
  gpu.Count = static_cast<GLsizei>(quads);
  gpu.Bytes = geometry.size() * sizeof(float) + planes.size() * sizeof(GLint) +
    6 * gpu.IndexedQuads * sizeof(GLuint);
  gpu.Version = version;
}

void vtkPARCRasterizer::vtkInternals::Draw(GLuint program, const GPUModel& gpu,
  const parc::Matrix4& indexToWorld, const vtkPARCRasterizer::View& view,
  const parc::Vec3& skipNormal)
{
  glUseProgram(program);
  SetVector(program, "SkipNormal", skipNormal);
  // The view's frame has the eye at its origin (see parc::vtk::MakePassView): the shaders' coordinates
  // stay small, and float never holds a large coordinate.
  SetMatrix(program, "IndexToRelative", indexToWorld);
  SetMatrix(program, "RelativeToClip", view.Camera.WorldToNDC);
  // A bound of the magnitudes in the float transform of any vertex.
  double linear = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      linear += indexToWorld(r, c) * indexToWorld(r, c);
    }
  }
  const double frameScale =
    parc::Length(parc::Vec3{ indexToWorld(0, 3), indexToWorld(1, 3), indexToWorld(2, 3) }) +
    std::sqrt(linear) * gpu.LargestCorner;
  SetVector(program, "ViewDirection", view.Camera.Direction);
  glUniform1f(glGetUniformLocation(program, "Empty"), parc::DepthBufferSource::Empty);
  glUniform1f(glGetUniformLocation(program, "FrameScale"), static_cast<float>(frameScale));
  SetVectors(program, "RayBase", view.RayBase);
  SetVectors(program, "RayDirection", view.RayDirection);
  glUniform2f(glGetUniformLocation(program, "PixelToNDC"), 2.0f / view.Camera.Width,
    2.0f / view.Camera.Height);
  // Without affine rays an infinite margin keeps every face's whole depth range.
  glUniform1f(glGetUniformLocation(program, "MarginScale"),
    view.AffineRays ? static_cast<float>(FaceDepthMargin * view.MaxRayDirectionLength)
                    : std::numeric_limits<float>::infinity());
  const float minDepth =
    view.Camera.Parallel ? -3.0e38f : static_cast<float>(NearClipFraction * view.Camera.NearDistance);
  glUniform1f(glGetUniformLocation(program, "MinDepth"), minDepth);
  glUniform2f(glGetUniformLocation(program, "Dilation"),
    static_cast<float>(2.0 * DilationPixels / view.Camera.Width),
    static_cast<float>(2.0 * DilationPixels / view.Camera.Height));
  glBindVertexArray(gpu.VertexArray);
  glDrawRangeElements(GL_TRIANGLES, 0, std::max(4 * gpu.Count, 1) - 1, 6 * gpu.Count,
    GL_UNSIGNED_INT, nullptr);
}

void vtkPARCRasterizer::vtkInternals::Release()
{
  if (this->Context && this->DepthProgram)
  {
    this->Context->MakeCurrent();
    glDeleteProgram(this->DepthProgram);
    glDeleteProgram(this->PlaneProgram);
    for (GPUModel& m : this->Models)
    {
      m.Release();
    }
    for (RenderTarget& t : this->Targets)
    {
      t.Release();
    }
  }
  this->DepthProgram = this->PlaneProgram = 0;
  for (RenderTarget& t : this->Targets)
  {
    t = RenderTarget();
  }
  for (GPUModel& m : this->Models)
  {
    m = GPUModel();
  }
  this->Driver = parc::vtk::DriverMemory(); // nothing of this rasterizer's is held any more
  this->Context = nullptr;
}

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkPARCRasterizer);

vtkPARCRasterizer::vtkPARCRasterizer()
  : Internals(new vtkInternals)
{
}

vtkPARCRasterizer::~vtkPARCRasterizer()
{
  this->Internals->Release();
}

bool vtkPARCRasterizer::HasModel(
  vtkRenderWindow* window, Pass pass, std::uint64_t modelVersion) const
{
  const vtkInternals& in = *this->Internals;
  return window && window == in.Context.GetPointer() &&
    in.Models[static_cast<int>(pass)].Version == modelVersion;
}

void vtkPARCRasterizer::ReleasePass(vtkRenderWindow* window, Pass pass)
{
  vtkInternals& in = *this->Internals;
  if (!window || window != in.Context.GetPointer() || !in.DepthProgram)
  {
    return;
  }
  const int slot = static_cast<int>(pass);
  if (!in.Models[slot].VertexArray && in.Targets[slot].GetMemorySize() == 0)
  {
    return; // nothing held
  }
  if (pass == Pass::Planes)
  {
    std::vector<std::uint32_t>().swap(in.Texels);
  }
  parc::vtk::DriverMemory::Scope measured(in.Driver);
  in.Context->MakeCurrent();
  in.Models[slot].Release();
  in.Targets[slot].Release();
  ++this->ReleaseCount;
}

double vtkPARCRasterizer::GetSetUpTime() const
{
  return this->Internals->SetUpTime;
}

std::size_t vtkPARCRasterizer::vtkInternals::GetObjectsMemorySize() const
{
  std::size_t bytes = 0;
  for (int slot = 0; slot < Passes; ++slot)
  {
    bytes += this->Models[slot].Bytes + this->Targets[slot].GetMemorySize();
  }
  return bytes;
}

std::size_t vtkPARCRasterizer::GetMemorySize() const
{
  const vtkInternals& in = *this->Internals;
  return in.Texels.capacity() * sizeof(std::uint32_t) + in.GetObjectsMemorySize();
}

std::size_t vtkPARCRasterizer::GetDriverMemorySize() const
{
  const vtkInternals& in = *this->Internals;
  const std::size_t measured = in.Driver.GetMemorySize();
  const std::size_t objects = in.GetObjectsMemorySize();
  return measured > objects ? measured - objects : 0;
}

void vtkPARCRasterizer::ReleaseGraphicsResources(vtkWindow* window)
{
  // Only the resources of that window's context: another window going away must not make
  // this context current behind VTK's back nor throw away what it still uses.
  if (!window || window == this->Internals->Context.GetPointer())
  {
    this->Internals->Release();
  }
}

//------------------------------------------------------------------------------
bool vtkPARCRasterizer::RenderLight(vtkRenderWindow* window, const parc::PolygonModel& model,
  std::uint64_t modelVersion, const parc::LightFrame& light, int resolution,
  const parc::SupercellGrid* grid, parc::LightBufferSource& source)
{
  source.Offset = -1.0 * light.Eye;
  source.Clear();
  for (const parc::Camera& camera : parc::LightCameras(light.Relative, light.Corners, resolution))
  {
    View view;
    view.Camera = camera;
    parc::vtk::SetRayCoefficients(view);
    view.AffineRays = false; // every face keeps its whole depth range: any line is covered
    bool ok;
    if (model.MajorAxis < 0)
    {
      std::vector<float> nearFar;
      ok = this->RenderDepth(window, model, modelVersion, light.IndexToLight, view, nearFar);
      source.Depth.emplace_back();
      source.Depth.back().Set(camera, std::move(nearFar), grid, light.LightToIndex);
    }
    else
    {
      std::vector<std::uint32_t> bits;
      int words = 0, passes = 0;
      constexpr int EveryFace = 0; // rays in both directions along the axis
      ok = this->RenderPlanes(
        window, model, modelVersion, light.IndexToLight, view, EveryFace, bits, words, passes);
      source.Planes.emplace_back();
      source.Planes.back().Set(camera, std::move(bits), words, grid, model.MajorAxis,
        model.FirstPlane, light.LightToIndex);
    }
    if (!ok)
    {
      source.Clear();
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkPARCRasterizer::RenderDepth(vtkRenderWindow* window, const parc::PolygonModel& model,
  std::uint64_t modelVersion, const parc::Matrix4& indexToWorld, const View& view,
  std::vector<float>& nearFar)
{
  vtkInternals& in = *this->Internals;
  const int w = view.Camera.Width, h = view.Camera.Height;
  nearFar.resize(2 * static_cast<std::size_t>(w) * h); // before Run: not the driver's memory
  return in.Run(window, "depth", this->LastError, [&](vtkOpenGLState* state) {
    const GPUModel& gpu = in.Use(Pass::Depth, model, modelVersion, this->UploadCount);
    if (!in.BindTarget(Pass::Depth, GL_RG32F, 1, w, h, this->LastError))
    {
      return false;
    }
    state->vtkglViewport(0, 0, w, h);
    glDisable(GL_COLOR_LOGIC_OP);
    const GLfloat clear[4] = { parc::DepthBufferSource::Empty, parc::DepthBufferSource::Empty,
      0.f, 0.f };
    glClearBufferfv(GL_COLOR, 0, clear);
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
    state->vtkglBlendEquation(GL_MIN);
    in.Draw(in.DepthProgram, gpu, indexToWorld, view, parc::Vec3());
    state->vtkglReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, w, h, GL_RG, GL_FLOAT, nearFar.data());
    return true;
  });
}

//------------------------------------------------------------------------------
bool vtkPARCRasterizer::RenderPlanes(vtkRenderWindow* window, const parc::PolygonModel& model,
  std::uint64_t modelVersion, const parc::Matrix4& indexToWorld, const View& view, int raySign,
  std::vector<std::uint32_t>& bits, int& wordsPerPixel, int& passes)
{
  parc::Vec3 skipNormal;
  if (model.MajorAxis >= 0)
  {
    skipNormal[model.MajorAxis] = raySign;
  }
  vtkInternals& in = *this->Internals;
  const int w = view.Camera.Width, h = view.Camera.Height;
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  passes = std::max(1, (model.PlaneCount + PlanesPerPass - 1) / PlanesPerPass);
  // Words per pixel: the planes' words in one attachment of one, two or four channels
  // (fewer bytes to blend and read back), else whole attachments of four.
  const int planeWords = std::max(1, (model.PlaneCount + 31) / 32);
  const int attachmentsTotal = (planeWords + 3) / 4;
  const TexelFormat texel = attachmentsTotal == 1 ? NarrowestTexel(planeWords) : WideTexel;
  wordsPerPixel = attachmentsTotal == 1 ? texel.Words : 4 * attachmentsTotal;
  // The read-back buffers are sized before Run: they are not the driver's memory.
  bits.resize(pixels * wordsPerPixel);
  std::vector<std::uint32_t>& texels = in.Texels;
  if (attachmentsTotal > 1)
  {
    texels.resize(4 * pixels);
  }
  return in.Run(window, "plane", this->LastError, [&](vtkOpenGLState* state) {
    const GPUModel& gpu = in.Use(Pass::Planes, model, modelVersion, this->UploadCount);
    state->vtkglDisable(GL_BLEND);
    for (int pass = 0; pass < passes; ++pass)
    {
      const int attachments = std::min(MaxAttachments, attachmentsTotal - pass * MaxAttachments);
      if (!in.BindTarget(Pass::Planes, texel.Internal, attachments, w, h, this->LastError))
      {
        return false;
      }
      state->vtkglViewport(0, 0, w, h);
      const GLuint zero[4] = { 0, 0, 0, 0 };
      for (int a = 0; a < attachments; ++a)
      {
        glClearBufferuiv(GL_COLOR, a, zero);
      }
      glEnable(GL_COLOR_LOGIC_OP);
      glLogicOp(GL_OR);
      glUseProgram(in.PlaneProgram);
      glUniform1i(glGetUniformLocation(in.PlaneProgram, "PlaneBase"), pass * PlanesPerPass);
      in.Draw(in.PlaneProgram, gpu, indexToWorld, view, skipNormal);
      for (int a = 0; a < attachments; ++a)
      {
        state->vtkglReadBuffer(GL_COLOR_ATTACHMENT0 + a);
        if (attachmentsTotal == 1)
        {
          glReadPixels(0, 0, w, h, texel.Format, GL_UNSIGNED_INT, bits.data());
          continue;
        }
        glReadPixels(0, 0, w, h, texel.Format, GL_UNSIGNED_INT, texels.data());
        const int word0 = 4 * (pass * MaxAttachments + a);
        for (std::size_t p = 0; p < pixels; ++p)
        {
          std::copy_n(texels.data() + 4 * p, 4, bits.data() + p * wordsPerPixel + word0);
        }
      }
    }
    return true;
  });
}

//------------------------------------------------------------------------------
void vtkPARCRasterizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "UploadCount: " << this->UploadCount << "\n";
  os << indent << "ReleaseCount: " << this->ReleaseCount << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
}
