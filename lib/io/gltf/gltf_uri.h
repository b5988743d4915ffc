// Which files a glTF reads (README "glTF"; lib/io/README.md "Which files a glTF reads"): its
// buffers' only, each inside the folder of the file that names it or inside a tree the run
// trusts (--allow-uri-outside), checked before tinygltf opens anything; tinygltf then reads
// through callbacks that open only the files so approved. Internal to io/ (tinygltf types).
#pragma once

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <tiny_gltf.h>

namespace skinslide {

/// `uri` percent-decoded as tinygltf 2.7 decodes it before it opens a file, so that what is
/// checked is what is opened: %XX is the byte 0xXX, and + is a space.
/// \return nullopt when a % is not followed by two hex digits, or the result holds a NUL byte
///         (a C path would end there; a %2e%2e is decoded, then confined like any `..`).
std::optional<std::string> percent_decoded(const std::string& uri);

/// True when `path` is `root` or lies under it, comparing whole components (/a/bc is not under
/// /a/b). \pre both absolute and normalised, without a trailing separator (as resolved below).
bool is_within(const std::filesystem::path& path, const std::filesystem::path& root);

/// The files a glTF's buffers may be read from, and those read.
struct ApprovedFiles {
  std::set<std::string> approved;  ///< resolved (weakly_canonical) paths
  std::vector<std::string> read;   ///< resolved paths of the files read, in read order
};

/// Checks every buffer URI of the glTF at `path` (`bytes`: its .gltf text or .glb bytes) and
/// approves the file each names. The rule: a data: URI that tinygltf decodes reads no file; a
/// URI with any other scheme (file:, http:, data: of a form tinygltf does not decode, C:) is
/// refused, as is one whose percent-decoding is malformed or holds a NUL, and one that decodes to
/// an absolute path. Any other URI is a path relative to the folder of `path`, resolved by
/// std::filesystem::weakly_canonical (`..` and symbolic links followed), and refused unless it
/// lies inside that folder (resolved the same way) or inside one of `allow_uri_outside`
/// (resolved against the working folder).
/// \throw Error(Input) "<path>: buffer <b> uri \"<uri>\": <what is wrong>; <the rule>".
/// \throw Error(Usage) for an empty entry of `allow_uri_outside`.
ApprovedFiles approved_buffer_files(const std::string& path, std::string_view bytes,
                                    const std::vector<std::string>& allow_uri_outside);

/// Filesystem callbacks for tinygltf::TinyGLTF::SetFsCallbacks that open only the regular files
/// in `files.approved` (each path resolved again when asked for), record each file read in
/// `files.read`, expand nothing (no `~`, no `$VAR`) and write nothing. Any other file, an
/// image's included, is "not found": tinygltf then keeps the image's URI and reads no byte of
/// it, and stops on a buffer. \pre `files` outlives the load.
tinygltf::FsCallbacks approved_files_only(ApprovedFiles& files);

}  // namespace skinslide
