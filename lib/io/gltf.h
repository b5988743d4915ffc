// glTF 2.0 (.gltf + .bin / data URIs, and .glb) in and out: io/gltf_read.h reads the surface and
// keeps the document, io/gltf_write.h writes it back with the slid vertices moved (and the static
// copies posed from it). With io/gltf_accessor, io/gltf_rig and io/gltf_weights, the only tinygltf
// users; neither header exposes tinygltf (GltfDocument is defined in io/gltf_document.h, included
// by io/*.cpp only).
#pragma once

#include "io/gltf_read.h"
#include "io/gltf_write.h"
