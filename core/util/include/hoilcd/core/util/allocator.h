// Process-wide tuning of glibc's allocator for loops that allocate frame-sized buffers on one
// thread and free them on another (rendering, benching). By default glibc gives freed memory
// at the top of a heap back to the kernel (madvise: a TLB shoot-down across cores, costly in a
// VM) and the next frame faults every page in again: ~10 % of a render's CPU (perf). Freed
// memory is kept for reuse instead; peak memory barely moves (a paper_room render: +8 %).
#pragma once

namespace hoilcd {

// Keeps freed memory up to 32 MiB per heap and serves allocations up to 32 MiB from the heap.
// Once per process; leaves the allocator alone when the user set MALLOC_TRIM_THRESHOLD_ or
// MALLOC_MMAP_THRESHOLD_, and does nothing on other C libraries.
void KeepFreedMemoryForReuse();

}  // namespace hoilcd
