// The option tables every client reads (core/option.h): each default inside its own range and
// among its own words, names distinct across the run's and every method's, so that a --config
// key, a keyword argument and a report key each name one option.
#include <set>

#include <gtest/gtest.h>

#include "pipeline/options.h"
#include "pipeline/run_options.h"

namespace skinslide {
namespace {

template <class Options>
void expect_defaults_valid(const OptionTable<Options>& table, std::set<std::string>& names) {
  const Options defaults{};
  EXPECT_NO_THROW(check_ranges(table, defaults));
  for (const Option<Options>& option : table) {
    EXPECT_TRUE(names.insert(option.name).second) << option.name << " declared twice";
    EXPECT_FALSE(option.help.empty()) << option.name;
    if (const auto* word = std::get_if<WordOption<Options>>(&option.value)) {
      const std::string name = word->get(defaults);
      EXPECT_NE(std::find(word->words.begin(), word->words.end(), name), word->words.end())
          << option.name << "'s default '" << name << "' is not one of its words";
      for (const std::string& w : word->words) {
        Options o = defaults;
        EXPECT_NO_THROW(word->set(o, w)) << option.name << " " << w;
      }
    }
  }
}

TEST(OptionTables, DefaultsAreValidAndNamesDistinct) {
  std::set<std::string> names;
  expect_defaults_valid(option_table<RunOptions>(), names);
  std::vector<std::string> methods;
  for_each_method([&](const std::string& method, const auto& table) {
    methods.push_back(method);
    expect_defaults_valid(table, names);
  });
  EXPECT_EQ(methods, (std::vector<std::string>{"elastic", "paper"}));
}

TEST(OptionTables, TheMethodOptionNamesEveryMethodAndSetsItsDefaults) {
  const auto& method = std::get<WordOption<RunOptions>>(method_option().value);
  EXPECT_EQ(method.words, (std::vector<std::string>{"elastic", "paper"}));
  RunOptions o;
  EXPECT_EQ(method.get(o), "elastic") << "the default method";
  method.set(o, "paper");
  ASSERT_TRUE(std::holds_alternative<PaperOptions>(o.slide));
  EXPECT_EQ(std::get<PaperOptions>(o.slide).cg_max_iterations, PaperOptions{}.cg_max_iterations);
  EXPECT_THROW(method.set(o, "papr"), Error);
}

TEST(OptionTables, OnlyTheLookupSizeServesEitherMethod) {
  for (const Option<PaperOptions>& option : option_table<PaperOptions>())
    EXPECT_EQ(option.run_wide, option.name == "lookup-size") << option.name;
  for (const Option<ElasticOptions>& option : option_table<ElasticOptions>())
    EXPECT_FALSE(option.run_wide) << option.name;
}

}  // namespace
}  // namespace skinslide
