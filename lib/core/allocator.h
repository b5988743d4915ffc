// Process-wide settings of the C library's allocator.
#pragma once

#include <string>
#include <string_view>

namespace skinslide {

/// Keeps freed memory in the process for reuse, in one arena shared by every thread.
///
/// Each frame allocates and frees the same large blocks (the numeric factor, the nets, the file
/// buffers). By default glibc maps blocks above a threshold afresh and unmaps them on free, trims
/// the heap's top, and gives each thread its own arena, so every frame touches new pages; on a
/// virtual machine a page fault is expensive. With freed memory kept and one arena, a frame
/// reuses the pages of the frame before, and the command's peak memory is lower (one arena holds
/// fewer idle blocks than one per thread); tests/bench/README.md "Performance" has the figures.
/// The threads allocate a few large blocks a frame, so sharing one arena's lock is cheap. Call
/// once, first thing in main().
/// \return false if the allocator rejected a setting (the others still apply)
bool keep_freed_memory();

/// Restarts the process image (same pid, arguments and descriptors) with glibc's heap backed by
/// transparent huge pages, when the kernel grants them only on request (THP mode `madvise`, the
/// Debian default) and glibc can ask (2.35 on). The set-up touches every page of its arrays once,
/// and one fault then maps 2 MiB instead of 4 KiB (tests/bench/README.md "Huge pages on the
/// farm"). Returns without restarting when there is nothing to gain or GLIBC_TUNABLES already
/// decides (`glibc.malloc.hugetlb=0` opts out), and when the restart fails. Call first in main(),
/// before any thread or output.
void restart_with_huge_pages(char** argv);

/// The decision behind restart_with_huge_pages, from what it reads: the contents of
/// /sys/kernel/mm/transparent_hugepage/enabled, the GLIBC_TUNABLES and LD_PRELOAD variables (null
/// when unset) and gnu_get_libc_version(). No restart under valgrind (its preload in LD_PRELOAD),
/// which would not follow it.
bool huge_pages_restart_wanted(std::string_view thp_enabled, const char* tunables,
                               const char* ld_preload, std::string_view glibc_version);

/// GLIBC_TUNABLES with the huge-page request appended to `tunables` (null when unset).
std::string tunables_with_huge_pages(const char* tunables);

}  // namespace skinslide
