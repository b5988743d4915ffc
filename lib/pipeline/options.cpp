#include "pipeline/options.h"

#include <array>
#include <utility>

#include "core/error.h"

namespace skinslide {

namespace {

// Each method's name, in SlideOptions' order.
constexpr std::array<const char*, std::variant_size_v<SlideOptions>> kMethodNames{"elastic",
                                                                                  "paper"};

// The default options of alternative `index`.
template <std::size_t... I>
SlideOptions defaults(std::size_t index, std::index_sequence<I...>) {
  SlideOptions options;
  ((index == I ? (void)options.emplace<I>() : void()), ...);
  return options;
}

}  // namespace

SlideOptions parse_method(const std::string& name) {
  std::string names;
  for (std::size_t i = 0; i < kMethodNames.size(); ++i) {
    if (name == kMethodNames[i])
      return defaults(i, std::make_index_sequence<std::variant_size_v<SlideOptions>>());
    names += (i ? ", " : "") + std::string(kMethodNames[i]);
  }
  throw Error(ErrorKind::Usage, "unknown method '" + name + "' (" + names + ")");
}

std::string method_name(const SlideOptions& options) { return kMethodNames[options.index()]; }

}  // namespace skinslide
