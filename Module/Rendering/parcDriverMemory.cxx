#include "parcDriverMemory.h"

#include <algorithm>
#include <cstdio>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <unistd.h>
#endif

namespace parc
{
namespace vtk
{

//------------------------------------------------------------------------------
DriverMemory::Scope::Scope(DriverMemory& memory)
  : Memory(memory)
  , Heap(HeapBytes())
  , Resident(ResidentBytes())
{
}

DriverMemory::Scope::~Scope()
{
  const std::int64_t heap = HeapBytes() - this->Heap;
  const std::int64_t resident = ResidentBytes() - this->Resident;
  this->Memory.Heap += heap;
  // Resident growth the heap's does not explain: the code pages and compiled code of a
  // shader compiler, or other mappings. A free lowers neither.
  this->Memory.Resident += std::max<std::int64_t>(0, resident - std::max<std::int64_t>(0, heap));
}

//------------------------------------------------------------------------------
std::size_t DriverMemory::GetMemorySize() const
{
  return static_cast<std::size_t>(std::max<std::int64_t>(0, this->Heap) + this->Resident);
}

//------------------------------------------------------------------------------
std::int64_t DriverMemory::HeapBytes()
{
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  const struct mallinfo2 info = mallinfo2();
  return static_cast<std::int64_t>(info.uordblks + info.hblkhd);
#else
  return 0;
#endif
}

std::int64_t DriverMemory::ResidentBytes()
{
#if defined(__linux__)
  std::FILE* statm = std::fopen("/proc/self/statm", "r");
  if (!statm)
  {
    return 0;
  }
  long size = 0, resident = 0;
  const bool read = std::fscanf(statm, "%ld %ld", &size, &resident) == 2;
  std::fclose(statm);
  return read ? static_cast<std::int64_t>(resident) * sysconf(_SC_PAGESIZE) : 0;
#else
  return 0;
#endif
}

}
}
