// PARC for VTK: the memory an OpenGL implementation keeps for the calls made to it, measured.
// No GL call says what its implementation allocates: a software GL such as Mesa's llvmpipe
// keeps a copy of every buffer and renderbuffer in the process, bins the triangles it draws
// and compiles shaders (its compiler's code pages and the code it makes become resident).
// DriverMemory measures it instead, around the calls that allocate, as the growth of the
// process's heap, of its resident file pages and of its other resident pages beyond the
// heap's.
#ifndef parcDriverMemory_h
#define parcDriverMemory_h

#include <cstddef>
#include <cstdint>

namespace parc
{
namespace vtk
{

class DriverMemory
{
public:
  /// Measures the calls made during its lifetime. Only the driver is to allocate then:
  /// the caller sizes its own buffers before (another thread allocating at the same time
  /// is counted too). Calls whose memory the driver frees outside them (a warm frame's)
  /// are not to be measured.
  class Scope;

  /// Bytes the measured calls hold: the heap they allocated and did not free, and what
  /// else they made resident (never less for a free: code pages stay).
  std::size_t GetMemorySize() const;

private:
  /// The process's memory at one time; 0 for what the system cannot tell.
  struct Snapshot
  {
    std::int64_t Heap = 0;           ///< bytes allocated from the heap (glibc)
    std::int64_t FilePages = 0;      ///< resident bytes backed by files (Linux)
    std::int64_t AnonymousPages = 0; ///< other resident bytes (Linux)
    static Snapshot Take();
  };
  std::int64_t Heap = 0;     ///< heap growth over the scopes (frees subtract)
  std::int64_t Resident = 0; ///< resident growth over the scopes beyond the heap's
};

class DriverMemory::Scope
{
public:
  explicit Scope(DriverMemory& memory);
  ~Scope();
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

private:
  DriverMemory& Memory;
  const Snapshot Before;
};

}
}

#endif
