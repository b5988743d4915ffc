#include "io/gltf/gltf_uri.h"

#include <cctype>
#include <fstream>

#include "core/error.h"
#include "io/gltf/gltf_buffer_uris.h"
#include "io/run_inputs.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

// Ends every refusal, so that the message names the rule it broke.
constexpr const char* kRule =
    "a glTF's buffers are read only from data: URIs and from files inside its own folder "
    "(--allow-uri-outside DIR trusts another tree)";

// A refused URI is quoted up to this many bytes: it may be a whole data: URI.
constexpr std::size_t kUriShown = 200;

[[noreturn]] void refuse(const std::string& path, std::size_t buffer, const std::string& uri,
                         const std::string& what) {
  const std::string shown = uri.size() <= kUriShown ? uri : uri.substr(0, kUriShown) + "...";
  throw Error(ErrorKind::Input, path + ": buffer " + std::to_string(buffer) + " uri \"" + shown +
                                    "\": " + what + "; " + kRule);
}

int hex_value(char ch) {
  if (ch >= '0' && ch <= '9') return ch - '0';
  if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
  if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
  return -1;
}

// RFC 3986 section 3.1: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":". A relative
// reference cannot start so (section 4.2: "./a:b.bin" can), so "C:/x.bin" has a scheme too.
std::optional<std::string> uri_scheme(const std::string& uri) {
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return std::nullopt;
  for (std::size_t i = 1; i < uri.size(); ++i) {
    const unsigned char ch = static_cast<unsigned char>(uri[i]);
    if (ch == ':') return uri.substr(0, i + 1);
    if (!std::isalnum(ch) && ch != '+' && ch != '-' && ch != '.') return std::nullopt;
  }
  return std::nullopt;
}

// `p` made absolute, with `..` and symbolic links resolved as far as it exists (the rest
// normalised lexically), and without a trailing separator, so that folders compare by components.
fs::path resolved(const fs::path& p, std::error_code& ec) {
  const fs::path absolute = fs::absolute(p, ec);
  if (ec) return {};
  fs::path r = fs::weakly_canonical(absolute, ec);
  if (!r.has_filename() && r.has_relative_path()) r = r.parent_path();
  return r;
}

std::vector<fs::path> trusted_trees(const std::vector<std::string>& allow_uri_outside) {
  std::vector<fs::path> trees;
  for (const std::string& dir : allow_uri_outside) {
    // An empty path would resolve to the working folder: say so rather than trust it silently.
    if (dir.empty()) throw Error(ErrorKind::Usage, "--allow-uri-outside: an empty folder name");
    std::error_code ec;
    trees.push_back(resolved(dir, ec));
    if (ec) throw Error(ErrorKind::Usage, "--allow-uri-outside " + dir + ": " + ec.message());
  }
  return trees;
}

// The file buffer `b`'s URI names, resolved, once it passes the rule.
fs::path buffer_file(const std::string& path, std::size_t b, const std::string& uri,
                     const fs::path& folder, const std::vector<fs::path>& trees) {
  if (const std::optional<std::string> scheme = uri_scheme(uri)) {
    std::string lower = *scheme;
    for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    refuse(path, b, uri,
           lower == "data:" ? "a data: URI tinygltf does not decode (it decodes base64 with a "
                              "media type such as application/octet-stream)"
                            : "the scheme " + *scheme + " (no scheme but data: is read)");
  }
  const std::optional<std::string> decoded = percent_decoded(uri);
  if (!decoded)
    refuse(path, b, uri, "malformed percent-encoding (a % without two hex digits, or %00)");
  if (fs::path(*decoded).has_root_path()) refuse(path, b, uri, "an absolute path");
  std::error_code ec;
  const fs::path file = resolved(folder / *decoded, ec);
  if (ec) refuse(path, b, uri, "cannot be resolved: " + ec.message());
  for (const fs::path& tree : trees)
    if (is_within(file, tree)) return file;
  refuse(path, b, uri,
         "resolves to " + file.string() + ", outside the glTF's folder " + trees.front().string() +
             (trees.size() > 1 ? " and the --allow-uri-outside trees" : ""));
}

std::optional<fs::path> approved_file(const std::string& asked, const ApprovedFiles& files) {
  std::error_code ec;
  const fs::path file = resolved(asked, ec);
  if (ec || files.approved.count(file.string()) == 0 || !fs::is_regular_file(file, ec))
    return std::nullopt;
  return file;
}

bool approved_exists(const std::string& asked, void* user) {
  return approved_file(asked, *static_cast<const ApprovedFiles*>(user)).has_value();
}

// As tinygltf 2.7's own: a URI's `~` or `$VAR` is a file name, not for a shell to expand.
std::string expand_nothing(const std::string& path, void*) { return path; }

bool read_approved(std::vector<unsigned char>* out, std::string* err, const std::string& asked,
                   void* user) {
  ApprovedFiles& files = *static_cast<ApprovedFiles*>(user);
  const std::optional<fs::path> file = approved_file(asked, files);
  std::error_code ec;
  const std::uintmax_t size = file ? fs::file_size(*file, ec) : 0;
  std::ifstream in;
  if (file && !ec) in.open(*file, std::ios::binary);
  if (!file || ec || !in) {
    if (err) *err += asked + ": not a file this glTF may read\n";
    return false;
  }
  out->resize(size);
  if (!in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
    if (err) *err += asked + ": cannot read\n";
    return false;
  }
  files.read.push_back(file->string());
  note_input(file->string());
  return true;
}

bool write_nothing(std::string* err, const std::string& path, const std::vector<unsigned char>&,
                   void*) {
  if (err) *err += path + ": the glTF reader writes no file\n";
  return false;
}

}  // namespace

std::optional<std::string> percent_decoded(const std::string& uri) {
  std::string out;
  out.reserve(uri.size());
  for (std::size_t i = 0; i < uri.size(); ++i) {
    char ch = uri[i];
    if (ch == '+') {
      ch = ' ';  // tinygltf 2.7 (dlib::urldecode) opens "a+b.bin" as "a b.bin"
    } else if (ch == '%') {
      const int hi = uri.size() - i > 2 ? hex_value(uri[i + 1]) : -1;
      const int lo = hi >= 0 ? hex_value(uri[i + 2]) : -1;
      if (lo < 0) return std::nullopt;
      ch = static_cast<char>(hi * 16 + lo);
      i += 2;
    }
    if (ch == '\0') return std::nullopt;
    out += ch;
  }
  return out;
}

bool is_within(const fs::path& path, const fs::path& root) {
  auto p = path.begin();
  for (auto r = root.begin(); r != root.end(); ++r, ++p)
    if (p == path.end() || *p != *r) return false;
  return true;
}

ApprovedFiles approved_buffer_files(const std::string& path, std::string_view bytes,
                                    const std::vector<std::string>& allow_uri_outside) {
  ApprovedFiles files;
  const std::optional<std::vector<std::string>> uris = gltf_buffer_uris(bytes);
  if (!uris) return files;  // nothing approved; tinygltf says what is wrong with the JSON
  const fs::path folder = fs::path(path).has_parent_path() ? fs::path(path).parent_path() : ".";
  std::error_code ec;
  std::vector<fs::path> trees = {resolved(folder, ec)};  // its own folder first
  if (ec) throw Error(ErrorKind::Input, path + ": cannot resolve its folder: " + ec.message());
  for (fs::path& tree : trusted_trees(allow_uri_outside)) trees.push_back(std::move(tree));
  for (std::size_t b = 0; b < uris->size(); ++b) {
    const std::string& uri = (*uris)[b];
    if (uri.empty() || tinygltf::IsDataURI(uri)) continue;  // no file: the GLB chunk, or data
    files.approved.insert(buffer_file(path, b, uri, folder, trees).string());
  }
  return files;
}

tinygltf::FsCallbacks approved_files_only(ApprovedFiles& files) {
  return {approved_exists, expand_nothing, read_approved, write_nothing, &files};
}

}  // namespace skinslide
