// Process-wide settings of the C library's allocator.
#pragma once

namespace skinslide {

/// Keeps freed memory in the process for reuse, in one arena shared by every thread.
///
/// Each frame allocates and frees the same large blocks (the numeric factor, the nets, the file
/// buffers). By default glibc maps blocks above a threshold afresh and unmaps them on free, trims
/// the heap's top, and gives each thread its own arena, so every frame touches new pages; on a
/// virtual machine a page fault is expensive. With freed memory kept and one arena, a frame
/// reuses the pages of the frame before: at 40k vertices a frame's net took 29 ms instead of
/// 70, and the command's peak memory went down (one arena holds fewer idle blocks than one per
/// thread; 490k vertices: 607 MB instead of 743). The threads allocate a few large blocks a
/// frame, so sharing one arena's lock costs nothing measurable. Call once, first thing in main().
/// \return false if the allocator rejected a setting (the others still apply)
bool keep_freed_memory();

}  // namespace skinslide
