#include "io/run_inputs.h"

#include <map>
#include <mutex>
#include <utility>

#include <sys/stat.h>

namespace skinslide {
namespace {

using Identity = std::pair<dev_t, ino_t>;

struct Registry {
  std::mutex mutex;
  int scopes = 0;
  std::map<Identity, std::string> read;  // identity -> the path it was first read as
};

Registry& registry() {
  static Registry r;
  return r;
}

std::optional<Identity> identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  return Identity{st.st_dev, st.st_ino};
}

}  // namespace

InputScope::InputScope() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  ++r.scopes;
}

InputScope::~InputScope() {
  Registry& r = registry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (--r.scopes == 0) r.read.clear();
}

void note_input(const std::string& path) {
  Registry& r = registry();
  const std::optional<Identity> id = identity(path);
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (r.scopes > 0 && id) r.read.emplace(*id, path);
}

std::optional<std::string> noted_input(const std::string& path) {
  Registry& r = registry();
  const std::optional<Identity> id = identity(path);
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (!id) return std::nullopt;
  const auto found = r.read.find(*id);
  if (found == r.read.end()) return std::nullopt;
  return found->second;
}

}  // namespace skinslide
