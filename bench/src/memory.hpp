#pragma once
// Memory measurement for plyfit-bench: a counter of live heap bytes behind a replacement of
// the global operator new/delete (every std container the kernel uses allocates through it),
// with a resettable peak; and the process's resident set size from /proc/self/status, with
// its high-water mark reset through /proc/self/clear_refs.

#include <cstddef>

namespace plyfit::bench::memory {

/// Heap bytes currently held through operator new (usable sizes of the malloc blocks).
std::size_t live_bytes();
/// Highest live_bytes() since the last reset_peak().
std::size_t peak_bytes();
/// Starts a new peak measurement at the current live_bytes().
void reset_peak();

/// Resident set size and its high-water mark (kilobytes), or -1 if unavailable.
long rss_kb();
long rss_peak_kb();
/// Resets the high-water mark to the current RSS (Linux >= 4.0); false if not possible.
bool reset_rss_peak();
/// Makes malloc return freed large blocks to the system at once (fixed mmap and trim
/// thresholds), so that RSS deltas of successive runs are comparable.
void stable_malloc();

}  // namespace plyfit::bench::memory
