#pragma once
// The process's own memory counters (Linux /proc), for tests that bound the memory of a call: reset the peak, run the
// call, read the peak.

#include <fstream>
#include <string>

namespace clothcd::test {

/// False under AddressSanitizer, whose allocator quarantine and shadow memory make the counters say nothing of the
/// library's own memory: bounds on them are then not checked.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kMemoryCountersMeaningful = false;
#else
inline constexpr bool kMemoryCountersMeaningful = true;
#endif

/// A field of /proc/self/status in bytes (e.g. "VmRSS", "VmHWM"), or -1 when there is none.
inline long status_bytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string name;
  long kilobytes = 0;
  while (status >> name) {
    if (name == field + ":" && status >> kilobytes) return kilobytes * 1024;
    status.ignore(1 << 12, '\n');
  }
  return -1;
}

/// Resident bytes now.
inline long resident_bytes() { return status_bytes("VmRSS"); }

/// Peak resident bytes since the last reset_peak_memory() (or since the start).
inline long peak_resident_bytes() { return status_bytes("VmHWM"); }

/// Sets the peak to the resident bytes now (writes 5 to /proc/self/clear_refs); false where that cannot be done.
inline bool reset_peak_memory() {
  std::ofstream clear_refs("/proc/self/clear_refs");
  clear_refs << "5";
  clear_refs.close();
  return static_cast<bool>(clear_refs);
}

}  // namespace clothcd::test
