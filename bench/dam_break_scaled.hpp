// SPDX-License-Identifier: BSD-3-Clause
// The 2D dam break of fluid_step.cpp (a 0.25 m x 0.5 m column in a 1 m x 0.6 m tank) refined to a
// given particle count for the scaling benchmarks, and the process's memory as Linux reports it.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>  // malloc_trim
#endif

namespace mpsfsi::bench {

// The water column holds 5,000 particles at l0 = 5 mm and the count goes as l0^-2; the tank's
// three layers add 1,338 at 5 mm but go as l0^-1 (2 % at 1e6 particles, 6 % at 1e5).
inline double dam_break_l0_for(double particles) { return 0.005 * std::sqrt(5000.0 / particles); }

// The benchmarks' time step at spacing l0: 2e-4 s at 5 mm (the example's), scaled with l0 so
// that the Courant number of the collapse stays that of the example.
inline double dam_break_dt_for(double l0) { return 2e-4 * l0 / 0.005; }

// A line "<key>: <n> kB" of /proc/self/status, in bytes; 0 where there is no such file.
inline double proc_status_bytes(const char* key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  const std::size_t length = std::strlen(key);
  while (std::getline(status, line))
    if (line.compare(0, length, key) == 0 && line.size() > length && line[length] == ':')
      return 1024.0 * std::stod(line.substr(length + 1));
  return 0;
}

// Resident memory now, and its peak since the last reset_peak_resident_bytes().
inline double resident_bytes() { return proc_status_bytes("VmRSS"); }
inline double peak_resident_bytes() { return proc_status_bytes("VmHWM"); }

// Resets the peak (Linux: writing 5 to /proc/self/clear_refs); false where that is not possible.
// First hands the heap's free memory back (glibc), so that what an earlier benchmark of the
// process freed does not count as resident before the next one starts.
inline bool reset_peak_resident_bytes() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
  std::FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  const bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}

}  // namespace mpsfsi::bench
