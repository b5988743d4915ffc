// glTF 2.0 (.gltf + .bin / data URIs, and .glb) in and out: io/gltf/gltf_read.h reads the surface
// and keeps the document, io/gltf/gltf_write.h writes it back with the slid vertices moved (and the
// static copies posed from it). With io/gltf/gltf_accessor, io/gltf/gltf_rig and
// io/gltf/gltf_weights, the only tinygltf users; neither header exposes tinygltf (GltfDocument is
// defined in io/gltf/gltf_document.h, included by io/gltf/*.cpp only).
#pragma once

#include "io/gltf/gltf_read.h"
#include "io/gltf/gltf_write.h"
