#include "io/gltf/gltf_buffer_uris.h"

#include <cstdint>

namespace skinslide {
namespace {

// A strict RFC 8259 reader that keeps only the buffers' URIs. It need not agree with tinygltf's
// parser (nlohmann::json) on every odd document: a URI it misses is a file never approved, which
// the reader's callbacks then refuse to open (io/gltf/gltf_uri.h). Recursive, depth-bounded.
struct Scan {
  std::string_view s;
  std::size_t i = 0;
  bool at_end() const { return i >= s.size(); }
  char peek() const { return s[i]; }
};

void skip_space(Scan& c) {
  while (!c.at_end() &&
         (c.peek() == ' ' || c.peek() == '\t' || c.peek() == '\n' || c.peek() == '\r'))
    ++c.i;
}

// The next non-space character, or 0 at the end.
char next(Scan& c) {
  skip_space(c);
  return c.at_end() ? '\0' : c.peek();
}

bool eat(Scan& c, char ch) {
  if (next(c) != ch) return false;
  ++c.i;
  return true;
}

int hex_value(char ch) {
  if (ch >= '0' && ch <= '9') return ch - '0';
  if (ch >= 'a' && ch <= 'f') return ch - 'a' + 10;
  if (ch >= 'A' && ch <= 'F') return ch - 'A' + 10;
  return -1;
}

bool read_hex4(Scan& c, std::uint32_t& v) {
  if (c.s.size() - c.i < 4) return false;
  v = 0;
  for (int k = 0; k < 4; ++k) {
    const int h = hex_value(c.s[c.i++]);
    if (h < 0) return false;
    v = v * 16 + static_cast<std::uint32_t>(h);
  }
  return true;
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// A data: URI's payload is not needed, and may be hundreds of megabytes.
bool keeps_more(const std::string& out) {
  return out.size() < kDataUriKept || out.compare(0, 5, "data:") != 0;
}

// The code point of the escape after a backslash (\uXXXX with its low surrogate, if any).
bool read_escape(Scan& c, std::uint32_t& cp) {
  if (c.at_end()) return false;
  switch (c.s[c.i++]) {
    case '"':
      cp = '"';
      return true;
    case '\\':
      cp = '\\';
      return true;
    case '/':
      cp = '/';
      return true;
    case 'b':
      cp = '\b';
      return true;
    case 'f':
      cp = '\f';
      return true;
    case 'n':
      cp = '\n';
      return true;
    case 'r':
      cp = '\r';
      return true;
    case 't':
      cp = '\t';
      return true;
    case 'u':
      break;
    default:
      return false;
  }
  if (!read_hex4(c, cp) || (cp >= 0xDC00 && cp <= 0xDFFF)) return false;  // a lone low half
  if (cp < 0xD800 || cp > 0xDBFF) return true;
  std::uint32_t low = 0;  // a high surrogate: its low half must follow
  if (c.s.substr(c.i, 2) != "\\u") return false;
  c.i += 2;
  if (!read_hex4(c, low) || low < 0xDC00 || low > 0xDFFF) return false;
  cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
  return true;
}

// A string at the cursor; its value appended to `out` unless null.
bool read_string(Scan& c, std::string* out) {
  if (!eat(c, '"')) return false;
  while (!c.at_end()) {
    const unsigned char ch = static_cast<unsigned char>(c.s[c.i++]);
    if (ch == '"') return true;
    if (ch < 0x20) return false;  // a control character must be escaped
    if (ch != '\\') {
      if (out && keeps_more(*out)) *out += static_cast<char>(ch);
      continue;
    }
    std::uint32_t cp = 0;
    if (!read_escape(c, cp)) return false;
    if (out && keeps_more(*out)) append_utf8(*out, cp);
  }
  return false;  // not terminated
}

bool read_number(Scan& c) {
  const auto digit = [&](std::size_t k) {
    return k < c.s.size() && c.s[k] >= '0' && c.s[k] <= '9';
  };
  std::size_t i = c.i;
  if (i < c.s.size() && c.s[i] == '-') ++i;
  if (!digit(i)) return false;
  if (c.s[i++] != '0')
    while (digit(i)) ++i;
  if (i < c.s.size() && c.s[i] == '.') {
    if (!digit(++i)) return false;
    while (digit(i)) ++i;
  }
  if (i < c.s.size() && (c.s[i] == 'e' || c.s[i] == 'E')) {
    ++i;
    if (i < c.s.size() && (c.s[i] == '+' || c.s[i] == '-')) ++i;
    if (!digit(i)) return false;
    while (digit(i)) ++i;
  }
  c.i = i;
  return true;
}

bool read_literal(Scan& c, std::string_view word) {
  if (c.s.substr(c.i, word.size()) != word) return false;
  c.i += word.size();
  return true;
}

// An object at the cursor (its own depth `depth`): `member(key)` reads each member's value.
template <class Member>
bool read_object(Scan& c, int depth, Member&& member) {
  if (depth > kMaxJsonDepth || !eat(c, '{')) return false;
  if (eat(c, '}')) return true;
  do {
    std::string key;
    if (!read_string(c, &key) || !eat(c, ':') || !member(key)) return false;
  } while (eat(c, ','));
  return eat(c, '}');
}

// An array at the cursor (its own depth `depth`): `element()` reads each element.
template <class Element>
bool read_array(Scan& c, int depth, Element&& element) {
  if (depth > kMaxJsonDepth || !eat(c, '[')) return false;
  if (eat(c, ']')) return true;
  do {
    if (!element()) return false;
  } while (eat(c, ','));
  return eat(c, ']');
}

// Any value at the cursor, inside a container of depth `depth`.
bool skip_value(Scan& c, int depth) {
  switch (next(c)) {
    case '"':
      return read_string(c, nullptr);
    case '{':
      return read_object(c, depth + 1,
                         [&](const std::string&) { return skip_value(c, depth + 1); });
    case '[':
      return read_array(c, depth + 1, [&] { return skip_value(c, depth + 1); });
    case 't':
      return read_literal(c, "true");
    case 'f':
      return read_literal(c, "false");
    case 'n':
      return read_literal(c, "null");
    default:
      return read_number(c);
  }
}

// One element of `buffers` (depth 2): its `uri` appended to `uris`, "" when it has none.
bool read_buffer(Scan& c, std::vector<std::string>& uris) {
  constexpr int kDepth = 3;
  std::string& uri = uris.emplace_back();
  if (next(c) != '{') return skip_value(c, kDepth - 1);
  bool seen = false;
  return read_object(c, kDepth, [&](const std::string& key) {
    if (key != "uri") return skip_value(c, kDepth);
    if (seen) return false;  // twice: which one tinygltf takes is its parser's business
    seen = true;
    return next(c) == '"' ? read_string(c, &uri) : skip_value(c, kDepth);
  });
}

std::optional<std::vector<std::string>> json_buffer_uris(std::string_view json) {
  Scan c{json};
  if (json.substr(0, 3) == "\xEF\xBB\xBF") c.i = 3;  // nlohmann::json skips a UTF-8 BOM too
  std::vector<std::string> uris;
  bool seen = false;
  const bool ok = read_object(c, 1, [&](const std::string& key) {
    if (key != "buffers") return skip_value(c, 1);
    if (seen) return false;
    seen = true;
    if (next(c) != '[') return skip_value(c, 1);
    return read_array(c, 2, [&] { return read_buffer(c, uris); });
  });
  skip_space(c);
  if (!ok || !c.at_end()) return std::nullopt;
  return uris;
}

// The JSON chunk of a GLB (glTF 2.0 section 4.4: a 12-byte header, then the chunk's length and
// type), found where tinygltf finds it.
std::optional<std::string_view> glb_json_chunk(std::string_view bytes) {
  constexpr std::size_t kJsonStart = 20;
  if (bytes.size() < kJsonStart) return std::nullopt;
  std::uint32_t length = 0;  // little-endian
  for (int k = 3; k >= 0; --k) length = length << 8 | static_cast<unsigned char>(bytes[12 + k]);
  if (length > bytes.size() - kJsonStart) return std::nullopt;
  return bytes.substr(kJsonStart, length);
}

// The properties glTF 2.0 defines as integers >= 0 (indices, offsets, counts, enums) in the
// objects skinslide reads or writes back. tinygltf reads a value that is not a JSON unsigned
// integer (-12, 1.5, "8") as absent: a byteOffset as 0, a bufferView as none. `[]` is any element
// of an array, `*` any key of an object.
constexpr std::string_view kIntegerProperties[] = {
    "scene",
    "scenes[].nodes[]",
    "nodes[].camera",
    "nodes[].children[]",
    "nodes[].skin",
    "nodes[].mesh",
    "meshes[].primitives[].attributes.*",
    "meshes[].primitives[].indices",
    "meshes[].primitives[].material",
    "meshes[].primitives[].mode",
    "meshes[].primitives[].targets[].*",
    "skins[].inverseBindMatrices",
    "skins[].skeleton",
    "skins[].joints[]",
    "animations[].channels[].sampler",
    "animations[].channels[].target.node",
    "animations[].samplers[].input",
    "animations[].samplers[].output",
    "accessors[].bufferView",
    "accessors[].byteOffset",
    "accessors[].componentType",
    "accessors[].count",
    "accessors[].sparse.count",
    "accessors[].sparse.indices.bufferView",
    "accessors[].sparse.indices.byteOffset",
    "accessors[].sparse.indices.componentType",
    "accessors[].sparse.values.bufferView",
    "accessors[].sparse.values.byteOffset",
    "bufferViews[].buffer",
    "bufferViews[].byteOffset",
    "bufferViews[].byteLength",
    "bufferViews[].byteStride",
    "bufferViews[].target",
    "buffers[].byteLength",
    "images[].bufferView",
    "textures[].sampler",
    "textures[].source",
};

// Whether the generic path of a value ("accessors[].byteOffset") is one of kIntegerProperties.
bool is_integer_property(std::string_view path) {
  for (std::string_view pattern : kIntegerProperties) {
    std::size_t i = 0, k = 0;
    while (i < pattern.size() && k <= path.size()) {
      if (pattern[i] == '*') {  // one key: up to the next '.' or '['
        while (k < path.size() && path[k] != '.' && path[k] != '[') ++k;
        ++i;
      } else if (k < path.size() && pattern[i] == path[k]) {
        ++i;
        ++k;
      } else {
        break;
      }
    }
    if (i == pattern.size() && k == path.size()) return true;
  }
  return false;
}

// Largest values tinygltf keeps: an index is read as an int, a size as a size_t.
constexpr unsigned long long kLargestIndex = 2147483647;
constexpr unsigned long long kLargestSize = 9223372036854775807;

bool is_size(std::string_view path) {
  for (std::string_view name : {"byteOffset", "byteLength", "count", "byteStride"})
    if (path.size() > name.size() && path.substr(path.size() - name.size()) == name &&
        path[path.size() - name.size() - 1] == '.')
      return true;
  return false;
}

// Walks the value at the cursor (inside a container of depth `depth`): `path` is its generic
// path, `where` its element name ("accessors[3].byteOffset"). The first integer property that is
// not a whole number in range goes to `fault`.
bool walk(Scan& c, int depth, std::string& path, std::string& where,
          std::optional<JsonFault>& fault) {
  const std::size_t start = c.i;
  const char first = next(c);
  const std::size_t path_size = path.size(), where_size = where.size();
  const auto restore = [&] {
    path.resize(path_size);
    where.resize(where_size);
  };
  bool ok = true;
  if (first == '{') {
    ok = read_object(c, depth + 1, [&](const std::string& key) {
      restore();
      path += (path.empty() ? "" : ".") + key;
      where += (where.empty() ? "" : ".") + key;
      return walk(c, depth + 1, path, where, fault);
    });
  } else if (first == '[') {
    std::size_t k = 0;
    ok = read_array(c, depth + 1, [&] {
      restore();
      path += "[]";
      where += "[" + std::to_string(k++) + "]";
      return walk(c, depth + 1, path, where, fault);
    });
  } else {
    ok = skip_value(c, depth);
  }
  restore();
  if (!ok || fault || first == '{' || first == '[' || !is_integer_property(path)) return ok;
  const std::string_view text = c.s.substr(start, c.i - start);
  std::string_view value = text;
  while (!value.empty() && (value.front() == ' ' || value.front() == '\t' ||
                            value.front() == '\n' || value.front() == '\r'))
    value.remove_prefix(1);
  const bool whole = !value.empty() && value.find_first_not_of("0123456789") == std::string::npos;
  constexpr std::size_t kShown = 40;
  const std::string shown(value.substr(0, kShown));
  if (!whole) {
    fault = JsonFault{where, shown + " is not a whole number >= 0"};
  } else {
    const unsigned long long limit = is_size(path) ? kLargestSize : kLargestIndex;
    unsigned long long x = 0;
    bool over = value.size() > 19;
    for (std::size_t k = 0; k < value.size() && !over; ++k) {
      over = x > (limit - static_cast<unsigned long long>(value[k] - '0')) / 10;
      x = x * 10 + static_cast<unsigned long long>(value[k] - '0');
    }
    if (over)
      fault =
          JsonFault{where, shown + " is past the largest " + (is_size(path) ? "size" : "index") +
                               " read (" + std::to_string(limit) + ")"};
  }
  return ok;
}

}  // namespace

std::optional<JsonFault> gltf_integer_fault(std::string_view bytes) {
  std::string_view json = bytes;
  if (bytes.substr(0, 4) == "glTF") {
    const std::optional<std::string_view> chunk = glb_json_chunk(bytes);
    if (!chunk) return std::nullopt;
    json = *chunk;
  }
  Scan c{json};
  if (json.substr(0, 3) == "\xEF\xBB\xBF") c.i = 3;
  std::string path, where;
  std::optional<JsonFault> fault;
  if (next(c) != '{' || !walk(c, 0, path, where, fault)) return std::nullopt;
  return fault;
}

std::optional<std::vector<std::string>> gltf_buffer_uris(std::string_view bytes) {
  if (bytes.substr(0, 4) != "glTF") return json_buffer_uris(bytes);
  const std::optional<std::string_view> json = glb_json_chunk(bytes);
  if (!json) return std::nullopt;
  return json_buffer_uris(*json);
}

}  // namespace skinslide
