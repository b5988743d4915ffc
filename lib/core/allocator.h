// Process-wide settings of the C library's allocator.
#pragma once

namespace skinslide {

/// Keeps freed memory in the process for reuse instead of returning it to the system.
///
/// Every frame allocates and frees the same large blocks (the numeric factor, the nets, the
/// file buffers). By default glibc maps blocks above a threshold afresh and unmaps them on free,
/// and trims the heap's top, so each frame touches new pages; on virtual machines a page fault is
/// expensive, and this halved the per-frame time at 40k vertices. Peak memory is unchanged: the
/// kept blocks are the ones the next frame reuses. Call once, first thing in main().
/// \return false if the allocator rejected a setting (nothing else changes)
bool keep_freed_memory();

}  // namespace skinslide
