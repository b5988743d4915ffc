#include "core/file_extension.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace skinslide {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace skinslide
