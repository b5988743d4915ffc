// Which files a glTF reads (io/gltf/gltf_uri.h, lib/io/README.md "Which files a glTF reads"): its
// buffers only, from inside its own folder or a trusted tree, checked before any byte is read.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/atomic_write.h"
#include "io/gltf/gltf.h"
#include "io/gltf/gltf_buffer_uris.h"
#include "io/gltf/gltf_document.h"
#include "io/gltf/gltf_test_util.h"
#include "io/gltf/gltf_uri.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;
using testing::temp_dir;

// One triangle's POSITION, 36 bytes: the only buffer a test glTF's mesh uses.
std::string triangle_bytes() {
  const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(p), sizeof p);
}

// A glTF whose buffer 0 (the triangle) is at `uri`, with `more` after it in `buffers` (each
// ",{...}") and `images` (the array's elements) if any.
std::string triangle_gltf(const std::string& uri, const std::string& more = "",
                          const std::string& images = "") {
  return R"({"asset": {"version": "2.0"},
  "buffers": [{"byteLength": 36, "uri": ")" +
         uri + "\"}" + more + R"(],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],)" +
         (images.empty() ? std::string() : "\n  \"images\": [" + images + "],") + R"(
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
}

// A data: URI holding the triangle's bytes.
std::string triangle_data_uri() {
  const std::string b = triangle_bytes();
  return "data:application/octet-stream;base64," +
         testing::base64(std::vector<unsigned char>(b.begin(), b.end()));
}

// The repro's shape: the mesh from a data URI, and a second buffer, used by nothing, at `uri`.
std::string leaking_gltf(const std::string& uri) {
  return triangle_gltf(triangle_data_uri(), R"(, {"byteLength": 36, "uri": ")" + uri + "\"}");
}

void write(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  write_file_atomic(path.string(), bytes);
}

// root/secret.bin outside root/asset/, the glTFs' folder; secret.bin has the triangle's size,
// so a read that reached it would succeed. root/asset/tri.bin is the triangle inside.
struct Layout {
  fs::path root = temp_dir();
  fs::path asset = root / "asset";
  fs::path secret = root / "secret.bin";
  Layout() {
    write(secret, triangle_bytes());
    write(asset / "tri.bin", triangle_bytes());
  }
  std::string gltf(const std::string& name, const std::string& text) const {
    write(asset / name, text);
    return (asset / name).string();
  }
};

// read_gltf_file refuses `path`: an input error naming the file, buffer `buffer`'s URI `uri`,
// `what` and the rule.
void expect_refused(const std::string& path, int buffer, const std::string& uri,
                    const std::string& what, const MeshReadOptions& options = {}) {
  try {
    read_gltf_file(path, options);
    ADD_FAILURE() << path << " was read; expected buffer " << buffer << " uri " << uri
                  << " to be refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    const std::string m = e.what();
    const std::string head = path + ": buffer " + std::to_string(buffer) + " uri \"" + uri + "\": ";
    EXPECT_EQ(m.rfind(head, 0), 0u) << m << "\nexpected it to start with " << head;
    EXPECT_NE(m.find(what), std::string::npos) << m << "\nexpected: " << what;
    EXPECT_NE(m.find("read only from data: URIs and from files inside its own folder"),
              std::string::npos)
        << m;
  }
}

// Enough ../ to climb from any temporary folder to /, then the absolute path without its /.
std::string climbing_to(const fs::path& target) {
  std::string up;
  for (int i = 0; i < 24; ++i) up += "../";
  return up + target.relative_path().string();
}

TEST(GltfUri, TraversalOutOfTheFolderIsRefused) {
  const Layout t;
  // The leak as first reported: an unused second buffer whose URI climbs to a file outside.
  const std::string uri = climbing_to(t.secret);
  expect_refused(t.gltf("climb.gltf", leaking_gltf(uri)), 1, uri,
                 "resolves to " + fs::weakly_canonical(t.secret).string() +
                     ", outside the glTF's folder " + fs::weakly_canonical(t.asset).string());
  expect_refused(t.gltf("up.gltf", leaking_gltf("../secret.bin")), 1, "../secret.bin",
                 "outside the glTF's folder");
  // The mesh's own buffer, and a sibling folder whose name starts like the asset's.
  expect_refused(t.gltf("mesh.gltf", triangle_gltf("../secret.bin")), 0, "../secret.bin",
                 "outside");
  write(t.root / "asset2" / "tri.bin", triangle_bytes());
  expect_refused(t.gltf("sibling.gltf", triangle_gltf("../asset2/tri.bin")), 0, "../asset2/tri.bin",
                 "outside");
}

// A GLB of `json` alone (no BIN chunk: every buffer has a URI).
std::string glb_of(const std::string& json) {
  std::string glb = "glTF";
  const auto u32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) glb += static_cast<char>((v >> (8 * k)) & 0xFF);
  };
  const std::string padded = json + std::string((4 - json.size() % 4) % 4, ' ');
  u32(2);
  u32(static_cast<std::uint32_t>(20 + padded.size()));
  u32(static_cast<std::uint32_t>(padded.size()));
  return glb + "JSON" + padded;
}

TEST(GltfUri, GlbBuffersFollowTheSameRule) {
  const Layout t;
  expect_refused(t.gltf("leak.glb", glb_of(leaking_gltf("../secret.bin"))), 1, "../secret.bin",
                 "outside the glTF's folder");
  const MeshFile f = read_gltf_file(t.gltf("inside.glb", glb_of(triangle_gltf("tri.bin"))), {});
  EXPECT_TRUE(f.gltf->binary);
  EXPECT_EQ(f.gltf->files_read,
            std::vector<std::string>{fs::weakly_canonical(t.asset / "tri.bin").string()});
}

// The URI is judged as JSON decodes it: \u002e is a dot.
TEST(GltfUri, JsonEscapedTraversalIsRefused) {
  const Layout t;
  expect_refused(t.gltf("escaped.gltf", leaking_gltf(R"(\u002e\u002e\/secret.bin)")), 1,
                 "../secret.bin", "outside the glTF's folder");
}

TEST(GltfUri, SymlinkInsideTheFolderPointingOutIsRefused) {
  const Layout t;
  fs::create_directory_symlink(t.root, t.asset / "link");
  expect_refused(t.gltf("link.gltf", leaking_gltf("link/secret.bin")), 1, "link/secret.bin",
                 "resolves to " + fs::weakly_canonical(t.secret).string() + ", outside");
  fs::create_symlink(t.secret, t.asset / "file_link.bin");
  expect_refused(t.gltf("file_link.gltf", triangle_gltf("file_link.bin")), 0, "file_link.bin",
                 "outside");
  // A link that stays inside is followed and read.
  fs::create_symlink(t.asset / "tri.bin", t.asset / "inside_link.bin");
  EXPECT_EQ(read_gltf_file(t.gltf("inside.gltf", triangle_gltf("inside_link.bin")), {})
                .mesh.vertex_count(),
            3);
}

TEST(GltfUri, AbsolutePathIsRefusedEvenBesideTheWorkingFolder) {
  const Layout t;
  const std::string uri = t.secret.string();
  expect_refused(t.gltf("abs.gltf", leaking_gltf(uri)), 1, uri, "an absolute path");
  // Named without a folder, the file's folder is the working one: tinygltf 2.7 alone then
  // opened the absolute path as it stands.
  const fs::path cwd = fs::current_path();
  fs::current_path(t.asset);
  expect_refused("abs.gltf", 1, uri, "an absolute path");
  fs::current_path(cwd);
}

TEST(GltfUri, SchemesOtherThanDataAreRefused) {
  const Layout t;
  const std::string file_uri = "file://" + t.secret.string();
  expect_refused(t.gltf("file.gltf", leaking_gltf(file_uri)), 1, file_uri, "the scheme file:");
  expect_refused(t.gltf("http.gltf", leaking_gltf("http://example.com/secret.bin")), 1,
                 "http://example.com/secret.bin", "the scheme http:");
  // A data: URI tinygltf cannot decode would be opened as a file named "data:...".
  expect_refused(t.gltf("text.gltf", leaking_gltf("data:text/plain,abc")), 1, "data:text/plain,abc",
                 "a data: URI tinygltf does not decode");
  expect_refused(t.gltf("drive.gltf", leaking_gltf("C:/secret.bin")), 1, "C:/secret.bin",
                 "the scheme C:");
}

TEST(GltfUri, PercentEncodedTraversalIsDecodedThenRefused) {
  const Layout t;
  for (const std::string uri : {"%2e%2e/secret.bin", "%2E%2E%2Fsecret.bin", "..%2fsecret.bin"})
    expect_refused(t.gltf("pct.gltf", leaking_gltf(uri)), 1, uri, "outside the glTF's folder");
  expect_refused(t.gltf("slash.gltf", leaking_gltf("%2f" + t.secret.relative_path().string())), 1,
                 "%2f" + t.secret.relative_path().string(), "an absolute path");
  // A % without two hex digits: tinygltf 2.7 reads %zz as a NUL byte, where a C path ends.
  expect_refused(t.gltf("nul.gltf", leaking_gltf("tri.bin%zz../secret.bin")), 1,
                 "tri.bin%zz../secret.bin", "malformed percent-encoding");
  expect_refused(t.gltf("nul2.gltf", leaking_gltf("tri.bin%00")), 1, "tri.bin%00",
                 "malformed percent-encoding");
}

TEST(GltfUri, DotDotThatStaysInsideIsRead) {
  const Layout t;
  fs::create_directories(t.asset / "meshes");
  for (const std::string uri : {"meshes/../tri.bin", "meshes/%2e%2e/tri.bin", "./tri.bin"}) {
    const MeshFile f = read_gltf_file(t.gltf("in.gltf", triangle_gltf(uri)), {});
    EXPECT_EQ(f.mesh.vertex_count(), 3) << uri;
    EXPECT_EQ(f.gltf->files_read,
              std::vector<std::string>{fs::weakly_canonical(t.asset / "tri.bin").string()});
  }
  // A real pattern, a glTF in a nested folder of the asset's tree reaching a sibling folder, is
  // outside the glTF's own folder: it takes --allow-uri-outside (AllowUriOutside... below).
  write(t.asset / "shared" / "body.bin", triangle_bytes());
  const fs::path nested = t.asset / "lod0" / "hero.gltf";
  write(nested, triangle_gltf("../shared/body.bin"));
  expect_refused(nested.string(), 0, "../shared/body.bin", "outside the glTF's folder");
}

// A thread that notices anyone opening `fifo` for reading: it polls for a reader with a
// non-blocking open for writing (ENXIO while there is none) and, if one appears, writes a byte
// and closes, which lets a blocked reader go on.
struct FifoWatch {
  explicit FifoWatch(const fs::path& fifo) : path(fifo.string()) {
    EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
    watcher = std::thread([this] {
      while (!done) {
        const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) {
          opened = true;
          (void)!::write(fd, "x", 1);
          ::close(fd);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    });
  }
  ~FifoWatch() { stop(); }
  void stop() {
    done = true;
    if (watcher.joinable()) watcher.join();
  }
  std::string path;
  std::atomic<bool> done{false}, opened{false};
  std::thread watcher;
};

TEST(GltfUri, ImagesAreNeverOpened) {
  const Layout t;
  write(t.asset / "tex" / "skin.png", "not read");
  FifoWatch fifo(t.asset / "tex" / "pipe.png");
  const std::string images =
      R"({"uri": "tex/skin.png"}, {"uri": "tex/pipe.png"}, {"uri": "../secret.bin"})";
  const MeshFile f = read_gltf_file(t.gltf("img.gltf", triangle_gltf("tri.bin", "", images)), {});
  fifo.stop();
  EXPECT_FALSE(fifo.opened) << "an image file was opened";
  // Kept as URIs, for the writer to rebase.
  ASSERT_EQ(f.gltf->model.images.size(), 3u);
  EXPECT_EQ(f.gltf->model.images[0].uri, "tex/skin.png");
  EXPECT_TRUE(f.gltf->model.images[0].image.empty());
  EXPECT_EQ(f.gltf->model.images[2].uri, "../secret.bin");
  EXPECT_EQ(f.gltf->files_read,
            std::vector<std::string>{fs::weakly_canonical(t.asset / "tri.bin").string()});
}

TEST(GltfUri, AllowUriOutsideAdmitsATrustedSiblingTree) {
  const Layout t;
  write(t.root / "shared" / "body.bin", triangle_bytes());
  fs::create_directories(t.root / "other");
  const std::string hero = t.gltf("hero.gltf", triangle_gltf("../shared/body.bin"));
  expect_refused(hero, 0, "../shared/body.bin", "outside the glTF's folder");
  const std::string shared = (t.root / "shared").string();
  const MeshFile f = read_gltf_file(hero, {"", {(t.root / "other").string(), shared}});
  EXPECT_EQ(f.gltf->files_read, std::vector<std::string>{
                                    fs::weakly_canonical(t.root / "shared" / "body.bin").string()});
  expect_refused(hero, 0, "../shared/body.bin", "outside", {"", {(t.root / "other").string()}});
  // The trusted tree is resolved too: a relative name, or one with .., names the same folder.
  const fs::path cwd = fs::current_path();
  fs::current_path(t.root);
  EXPECT_EQ(read_gltf_file(hero, {"", {"shared"}}).mesh.vertex_count(), 3);
  EXPECT_EQ(read_gltf_file(hero, {"", {"other/../shared/"}}).mesh.vertex_count(), 3);
  fs::current_path(cwd);
  // Resolution comes before the comparison: climbing out of the trusted tree is refused, and an
  // absolute path is refused whatever is trusted.
  expect_refused(t.gltf("climb.gltf", leaking_gltf("../shared/../secret.bin")), 1,
                 "../shared/../secret.bin", "outside", {"", {shared}});
  const std::string abs = (t.root / "shared" / "body.bin").string();
  expect_refused(t.gltf("abs.gltf", leaking_gltf(abs)), 1, abs, "an absolute path", {"", {shared}});
  try {
    read_gltf_file(hero, {"", {""}});
    ADD_FAILURE() << "an empty --allow-uri-outside was taken";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage) << e.what();
  }
}

TEST(GltfUri, PercentDecodingIsTinygltfsAndRefusesWhatCannotBeAPath) {
  EXPECT_EQ(percent_decoded("body.bin"), "body.bin");
  EXPECT_EQ(percent_decoded("my%20body%2Ebin"), "my body.bin");
  EXPECT_EQ(percent_decoded("%2e%2e%2Fx"), "../x");
  EXPECT_EQ(percent_decoded("a+b.bin"), "a b.bin");  // as tinygltf 2.7 opens it
  EXPECT_EQ(percent_decoded("%C3%A9"), "\xC3\xA9");
  EXPECT_EQ(percent_decoded(""), "");
  for (const std::string& bad :
       std::vector<std::string>{"%", "a%2", "%zz", "%2g", "100%", "%00", std::string("a\0b", 3)})
    EXPECT_EQ(percent_decoded(bad), std::nullopt) << bad;
}

TEST(GltfUri, WithinComparesWholeComponents) {
  EXPECT_TRUE(is_within("/a/b/c.bin", "/a/b"));
  EXPECT_TRUE(is_within("/a/b/c/d.bin", "/a/b"));
  EXPECT_TRUE(is_within("/a/b", "/a/b"));
  EXPECT_TRUE(is_within("/x.bin", "/"));
  EXPECT_FALSE(is_within("/a/bc/d.bin", "/a/b"));
  EXPECT_FALSE(is_within("/a/x.bin", "/a/b"));
  EXPECT_FALSE(is_within("/a", "/a/b"));
}

TEST(GltfUri, BufferUrisComeFromTheJsonOrTheGlbChunk) {
  using Uris = std::optional<std::vector<std::string>>;
  EXPECT_EQ(gltf_buffer_uris(R"({"buffers": [{"uri": "a.bin", "byteLength": 4}, {"byteLength": 4},
    {"name": {"uri": "not this"}, "uri": "b\u002e\u002e\/c \ud83d\ude00.bin"}, 7]})"),
            (Uris{{"a.bin", "", "b../c \xF0\x9F\x98\x80.bin", ""}}));
  // Only the top level's `buffers`; anything else is skipped, whatever it holds.
  EXPECT_EQ(gltf_buffer_uris(R"( {"asset": {"buffers": [{"uri": "x"}]}, "n": [-1.5e+3, true, null,
    "\"q\""], "buffers": [{"uri": 5}, {"uri": "d.bin"}]} )"),
            (Uris{{"", "d.bin"}}));
  EXPECT_EQ(gltf_buffer_uris(R"({"asset": {"version": "2.0"}})"),
            (Uris{std::vector<std::string>{}}));
  EXPECT_EQ(gltf_buffer_uris("\xEF\xBB\xBF{\"buffers\": [{\"uri\": \"e.bin\"}]}"),
            (Uris{{"e.bin"}}));
  // A data: URI is kept to its start.
  const std::string data = "data:application/octet-stream;base64," + std::string(5000, 'A');
  const Uris kept = gltf_buffer_uris(R"({"buffers": [{"uri": ")" + data + "\"}]}");
  ASSERT_TRUE(kept.has_value());
  ASSERT_EQ(kept->size(), 1u);
  EXPECT_GE(kept->front().size(), kDataUriKept);
  EXPECT_LT(kept->front().size(), kDataUriKept + 8);
  EXPECT_EQ(data.rfind(kept->front(), 0), 0u);
  // A GLB: its JSON chunk.
  const std::string json = R"({"buffers": [{"byteLength": 4}, {"uri": "../x.bin"}]})";
  std::string glb("glTF\x02\x00\x00\x00\x00\x00\x00\x00", 12);
  glb += static_cast<char>(json.size());
  glb += std::string(3, '\0') + "JSON" + json;
  EXPECT_EQ(gltf_buffer_uris(glb), (Uris{{"", "../x.bin"}}));
  EXPECT_EQ(gltf_buffer_uris(glb.substr(0, 19)), std::nullopt);
  EXPECT_EQ(gltf_buffer_uris(glb.substr(0, glb.size() - 1)), std::nullopt);
}

TEST(GltfUri, BufferUriScanRefusesWhatIsNotStrictJson) {
  for (const std::string bad :
       {"", "{", "[]", R"({"buffers": [{"uri": "a"}]} x)", R"({"buffers": [{"uri": "a"},]})",
        R"({"buffers": [{"uri": "a\x"}]})", R"({"buffers": [{"uri": "\ud83d"}]})",
        R"({"buffers": [{"uri": "\ude00"}]})", "{\"buffers\": [{\"uri\": \"a\nb\"}]}",
        R"({"n": 01})", R"({"n": 1.})", R"({"n": -})", R"({"n": tru})", R"({'buffers': []})",
        R"({"buffers": [{"uri": "a", "uri": "b"}]})", R"({"buffers": [], "buffers": []})"})
    EXPECT_EQ(gltf_buffer_uris(bad), std::nullopt) << bad;
  const std::string deep = std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']');
  EXPECT_EQ(gltf_buffer_uris("{\"n\": " + deep + "}"), std::nullopt);
  const std::string shallow = std::string(100, '[') + std::string(100, ']');
  EXPECT_TRUE(gltf_buffer_uris("{\"n\": " + shallow + "}").has_value());
}

TEST(GltfUri, CallbacksOpenOnlyApprovedRegularFiles) {
  const Layout t;
  ApprovedFiles files;
  files.approved.insert(fs::weakly_canonical(t.asset / "tri.bin").string());
  files.approved.insert(fs::weakly_canonical(t.asset).string());  // a folder is never opened
  const tinygltf::FsCallbacks fs_cb = approved_files_only(files);
  const std::string inside = (t.asset / "meshes" / ".." / "tri.bin").string();
  EXPECT_TRUE(fs_cb.FileExists(inside, fs_cb.user_data));
  EXPECT_FALSE(fs_cb.FileExists(t.secret.string(), fs_cb.user_data));
  EXPECT_FALSE(fs_cb.FileExists(t.asset.string(), fs_cb.user_data));
  EXPECT_EQ(fs_cb.ExpandFilePath("~/$HOME/x", fs_cb.user_data), "~/$HOME/x");
  std::vector<unsigned char> bytes;
  std::string err;
  EXPECT_FALSE(fs_cb.ReadWholeFile(&bytes, &err, t.secret.string(), fs_cb.user_data));
  EXPECT_NE(err.find("not a file this glTF may read"), std::string::npos) << err;
  EXPECT_TRUE(files.read.empty());
  ASSERT_TRUE(fs_cb.ReadWholeFile(&bytes, &err, inside, fs_cb.user_data)) << err;
  EXPECT_EQ(std::string(bytes.begin(), bytes.end()), triangle_bytes());
  EXPECT_EQ(files.read, std::vector<std::string>{fs::weakly_canonical(inside).string()});
  EXPECT_FALSE(fs_cb.WriteWholeFile(&err, (t.asset / "w.bin").string(), bytes, fs_cb.user_data));
  EXPECT_FALSE(fs::exists(t.asset / "w.bin"));
}

// tinygltf reads an integer property that is not a JSON whole number as absent: refused first.
TEST(GltfJson, IntegerPropertiesMustBeWholeNumbersInRange) {
  const auto fault = [](const std::string& json) {
    const std::optional<JsonFault> f = gltf_integer_fault(json);
    return f ? f->element + ": " + f->what : std::string();
  };
  EXPECT_EQ(fault(R"({"accessors":[{"byteOffset":0,"count":4},{"bufferView":1,"count":3}]})"), "");
  EXPECT_EQ(fault(R"({"accessors":[{"count":4},{"byteOffset":-12}]})"),
            "accessors[1].byteOffset: -12 is not a whole number >= 0");
  EXPECT_EQ(fault(R"({"bufferViews":[{"byteStride":1.5}]})"),
            "bufferViews[0].byteStride: 1.5 is not a whole number >= 0");
  EXPECT_EQ(fault(R"({"accessors":[{"count": "4"}]})"),
            "accessors[0].count: \"4\" is not a whole number >= 0");
  EXPECT_EQ(fault(R"({"accessors":[{"count":4e0}]})"),
            "accessors[0].count: 4e0 is not a whole number >= 0");
  EXPECT_EQ(fault(R"({"nodes":[{"children":[1, -1]}]})"),
            "nodes[0].children[1]: -1 is not a whole number >= 0");
  EXPECT_EQ(fault(R"({"meshes":[{"primitives":[{"targets":[{"NORMAL":null}]}]}]})"),
            "meshes[0].primitives[0].targets[0].NORMAL: null is not a whole number >= 0");
  EXPECT_EQ(fault(R"({"skins":[{"joints":[2147483648]}]})"),
            "skins[0].joints[0]: 2147483648 is past the largest index read (2147483647)");
  EXPECT_EQ(fault(R"({"buffers":[{"byteLength":4294967296}]})"), "");  // a size may pass 2^31
  // Pretty-printed: the spaces around a value are not part of it.
  EXPECT_EQ(fault("{\n  \"scenes\": [ { \"nodes\": [\n 0 ,\n 1\n ] } ],\n \"scene\" : 0\n}\n"), "");
  EXPECT_EQ(fault("{\n  \"scene\" :\n  -1\n}\n"), "scene: -1 is not a whole number >= 0");
  // Properties of the same name elsewhere (extras, extensions) are not glTF's to check.
  EXPECT_EQ(fault(R"({"extras":{"count":-1},"accessors":[{"extras":{"byteOffset":1.5}}]})"), "");
  EXPECT_EQ(fault(R"({"accessors":[{"byteOffset":-1)"), "");  // malformed: tinygltf reports it
}

}  // namespace
}  // namespace skinslide
