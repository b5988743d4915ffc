// The buffers' URIs of a glTF, read from its JSON before tinygltf loads anything, so that each is
// checked (io/gltf_uri.h) before a byte of it is read. Internal to io/.
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

/// Bytes of a data: URI kept by gltf_buffer_uris: more than the longest media type prefix
/// tinygltf decodes ("data:application/octet-stream;base64,", 37 bytes).
inline constexpr std::size_t kDataUriKept = 64;

/// Arrays and objects nested deeper are not scanned (a glTF nests about 6 deep; the scanner
/// recurses, and its stack must stay bounded whatever the input).
inline constexpr int kMaxJsonDepth = 512;

}  // namespace skinslide
