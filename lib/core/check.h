// SKINSLIDE_CHECK: an invariant that holds unless skinslide has a bug; on in release builds.
#pragma once

#include <string>

#include "core/error.h"

#define SKINSLIDE_CHECK(cond, msg)                                                      \
  do {                                                                                  \
    if (!(cond))                                                                        \
      throw ::skinslide::Error(::skinslide::ErrorKind::Internal,                        \
                               std::string(__FILE__) + ":" + std::to_string(__LINE__) + \
                                   ": internal error: " + (msg) + " (" #cond ")");      \
  } while (0)
