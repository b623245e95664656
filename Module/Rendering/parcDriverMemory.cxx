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
  , Before(Snapshot::Take())
{
}

DriverMemory::Scope::~Scope()
{
  const Snapshot after = Snapshot::Take();
  const std::int64_t heap = after.Heap - this->Before.Heap;
  this->Memory.Heap += heap;
  // Pages of files made resident (a shader compiler's code), and anonymous pages beyond
  // the heap's growth (compiled code, other mappings). A free lowers neither; heap
  // allocations that reuse pages already resident hide anonymous pages, never file pages.
  const std::int64_t file = after.FilePages - this->Before.FilePages;
  const std::int64_t anonymous = after.AnonymousPages - this->Before.AnonymousPages;
  this->Memory.Resident += std::max<std::int64_t>(0, file) +
    std::max<std::int64_t>(0, anonymous - std::max<std::int64_t>(0, heap));
}

//------------------------------------------------------------------------------
std::size_t DriverMemory::GetMemorySize() const
{
  return static_cast<std::size_t>(std::max<std::int64_t>(0, this->Heap) + this->Resident);
}

//------------------------------------------------------------------------------
DriverMemory::Snapshot DriverMemory::Snapshot::Take()
{
  Snapshot now;
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  const struct mallinfo2 info = mallinfo2();
  now.Heap = static_cast<std::int64_t>(info.uordblks + info.hblkhd);
#endif
#if defined(__linux__)
  // Pages: total, resident, resident and shared (backed by files).
  if (std::FILE* statm = std::fopen("/proc/self/statm", "r"))
  {
    long size = 0, resident = 0, shared = 0;
    if (std::fscanf(statm, "%ld %ld %ld", &size, &resident, &shared) == 3)
    {
      const std::int64_t page = sysconf(_SC_PAGESIZE);
      now.FilePages = shared * page;
      now.AnonymousPages = (resident - shared) * page;
    }
    std::fclose(statm);
  }
#endif
  return now;
}

}
}
