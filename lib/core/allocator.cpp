#include "core/allocator.h"

#include <gnu/libc-version.h>
#include <malloc.h>
#include <unistd.h>

#include <charconv>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <utility>

namespace skinslide {

bool keep_freed_memory() {
  constexpr int kHuge = 1 << 30;  // bytes: above any block a frame of a 1M-vertex patch needs
  const bool mapped = mallopt(M_MMAP_THRESHOLD, kHuge) == 1;
  const bool trimmed = mallopt(M_TRIM_THRESHOLD, kHuge) == 1;
  const bool one_arena = mallopt(M_ARENA_MAX, 1) == 1;
  return mapped && trimmed && one_arena;
}

namespace {

constexpr std::string_view kHugePageTunable = "glibc.malloc.hugetlb";

// "2.36" -> {2, 36}; anything unparsable -> {0, 0}.
std::pair<int, int> version_of(std::string_view text) {
  int major = 0, minor = 0;
  const char* end = text.data() + text.size();
  auto [dot, ec] = std::from_chars(text.data(), end, major);
  if (ec != std::errc() || dot == end || *dot != '.') return {0, 0};
  if (std::from_chars(dot + 1, end, minor).ec != std::errc()) return {0, 0};
  return {major, minor};
}

}  // namespace

bool huge_pages_restart_wanted(std::string_view thp_enabled, const char* tunables,
                               const char* ld_preload, std::string_view glibc_version) {
  // "always [madvise] never": the bracketed word is the mode in force.
  if (thp_enabled.find("[madvise]") == std::string_view::npos) return false;
  if (tunables && std::string_view(tunables).find(kHugePageTunable) != std::string_view::npos)
    return false;
  if (ld_preload && std::string_view(ld_preload).find("vgpreload") != std::string_view::npos)
    return false;
  return version_of(glibc_version) >= std::pair{2, 35};
}

std::string tunables_with_huge_pages(const char* tunables) {
  std::string out = tunables && *tunables ? std::string(tunables) + ":" : std::string();
  return out + std::string(kHugePageTunable) + "=1";
}

void restart_with_huge_pages(char** argv) {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::stringstream thp;
  thp << file.rdbuf();
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (!huge_pages_restart_wanted(thp.str(), tunables, std::getenv("LD_PRELOAD"),
                                 gnu_get_libc_version()))
    return;
  if (setenv("GLIBC_TUNABLES", tunables_with_huge_pages(tunables).c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: /proc is missing or the binary cannot be run again. The variable now names the
  // tunable, so no child would try again; run on with the pages as they are.
}

}  // namespace skinslide
