// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RawVector.h
 * @brief Internal to Core/Render: large per-Gaussian buffers that are not cleared when they
 * grow (RawVector: every element is written before it is read, by the parallel loop that fills
 * it, which so also touches the fresh pages in parallel instead of a serial clearing), kept
 * between calls with slack (ResizeKeep) and on transparent huge pages (HugePages). Not
 * installed.
 */
#ifndef vis4gs_RawVector_h
#define vis4gs_RawVector_h

#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace vis4gs
{
namespace raster
{
namespace internal
{

/// madvise(MADV_HUGEPAGE) on the whole 2 MiB pages of a large buffer (before first touch).
void HugePages(const void* data, std::size_t bytes);

/// std::allocator whose value-initialisation (resize(n)) is a default-initialisation: no
/// clearing of trivial types.
template <typename U>
struct DefaultInitAllocator : std::allocator<U>
{
  template <typename V>
  struct rebind
  {
    using other = DefaultInitAllocator<V>;
  };
  DefaultInitAllocator() = default;
  template <typename V>
  DefaultInitAllocator(const DefaultInitAllocator<V>&) noexcept
  {
  }
  template <typename V>
  void construct(V* p) noexcept
  {
    ::new (static_cast<void*>(p)) V;
  }
  template <typename V, typename... A>
  void construct(V* p, A&&... a)
  {
    ::new (static_cast<void*>(p)) V(std::forward<A>(a)...);
  }
};

template <typename U>
using RawVector = std::vector<U, DefaultInitAllocator<U>>;

/// Resizes @p v to @p n, keeping its memory when it is large enough (no clearing). A new
/// allocation gets 1/8 of slack: per-view sizes (visible Gaussians, tile pairs) vary from
/// view to view, and growing by a few elements must not re-allocate (and page-fault) the
/// whole buffer for every new maximum.
template <typename U, typename A>
void ResizeKeep(std::vector<U, A>& v, std::size_t n)
{
  if (v.size() != n)
  {
    if (v.capacity() < n)
    {
      const std::size_t capacity = n + n / 8;
      std::vector<U, A>().swap(v);
      v.reserve(capacity);
      HugePages(v.data(), capacity * sizeof(U));
    }
    v.resize(n);
  }
}

} // namespace internal
} // namespace raster
} // namespace vis4gs

#endif
