#include "pipeline/options.h"

#include "core/error.h"

namespace skinslide {

SlideOptions parse_method(const std::string& name) {
  if (name == "elastic") return ElasticOptions{};
  if (name == "paper") return PaperOptions{};
  throw Error(ErrorKind::Usage, "unknown method '" + name + "' (elastic, paper)");
}

std::string method_name(const SlideOptions& options) {
  return std::holds_alternative<PaperOptions>(options) ? "paper" : "elastic";
}

}  // namespace skinslide
