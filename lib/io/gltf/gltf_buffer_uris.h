// What is read of a glTF's JSON before tinygltf loads anything: the buffers' URIs, so that each
// is checked (io/gltf/gltf_uri.h) before a byte of it is read, and the integer properties tinygltf
// would read as absent when they are not whole numbers. Internal to io/.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace skinslide {

/// The `uri` of each element of the top-level `buffers` array, in order, JSON escapes decoded; ""
/// for an element without a string `uri` (a GLB's BIN chunk). `bytes` is a .gltf's text or a
/// .glb's bytes (GLB magic: the JSON chunk is read). A data: URI is kept to its first
/// kDataUriKept bytes (enough to tell what it is; its payload can be hundreds of megabytes).
/// \return nullopt when the JSON is malformed (RFC 8259), nested deeper than kMaxJsonDepth, has
///         `buffers` or a buffer's `uri` twice, or the GLB header is cut: then no buffer is
///         approved, and tinygltf, which parses the same bytes, reports what is wrong.
std::optional<std::vector<std::string>> gltf_buffer_uris(std::string_view bytes);

/// A value of a glTF's JSON that skinslide refuses, and where it is.
struct JsonFault {
  std::string element;  ///< e.g. "accessors[3].byteOffset"
  std::string what;     ///< e.g. "-12 is not a whole number >= 0"
};

/// The first property glTF 2.0 defines as an integer >= 0 (an index, offset, count, stride or
/// enum of the scene, nodes, meshes, skins, animations, accessors, buffer views, buffers, images
/// and textures) whose value is not a JSON whole number, or is past what tinygltf keeps (an index
/// 2^31 - 1, a size 2^63 - 1). tinygltf reads such a value as absent (a byteOffset of -12 or 1.5
/// as 0), which would change what the file means. `bytes` as for gltf_buffer_uris.
/// \return nullopt when every such value is whole and in range, or the JSON is malformed
///         (tinygltf then reports what is wrong).
std::optional<JsonFault> gltf_integer_fault(std::string_view bytes);

/// Bytes of a data: URI kept by gltf_buffer_uris: more than the longest media type prefix
/// tinygltf decodes ("data:application/octet-stream;base64,", 37 bytes).
inline constexpr std::size_t kDataUriKept = 64;

/// Arrays and objects nested deeper are not scanned (a glTF nests about 6 deep; the scanner
/// recurses, and its stack must stay bounded whatever the input).
inline constexpr int kMaxJsonDepth = 512;

}  // namespace skinslide
