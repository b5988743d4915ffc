// Named figures: what a report says, as data. The JSON report writes them as its members in the
// order given (pipeline/report.h), the Python module as dict entries; the methods and the run
// name them (elastic/elastic_method.h, paper/paper_method.h, pipeline/slide_frame.h).
#pragma once

#include <string>
#include <variant>
#include <vector>

namespace skinslide {

using FigureValue = std::variant<long long, double, bool, std::string, std::vector<long long>>;

struct Figure {
  std::string key;
  FigureValue value;
};

using Figures = std::vector<Figure>;

}  // namespace skinslide
