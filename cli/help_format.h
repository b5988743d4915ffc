// `--help` of skinslide, `skinslide compare` and `skinslide join`: CLI11's help laid out in our
// words, for a terminal or a farm log 100 columns wide.
#pragma once

#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

namespace skinslide::cli {

/// The widest a help line is (README "Options" is the reference; tests/cli/help_readme.py).
constexpr std::size_t kHelpColumns = 100;

/// The text wrapped at word boundaries to lines of at most `width` columns. Each "\n" ends a
/// paragraph; a paragraph starting with spaces (an example command) is kept as it is. Every line
/// but the first starts with `indent` spaces (the first: as `first_used` columns are already
/// taken); a word longer than a line stands alone on its own.
std::string wrap_text(const std::string& text, std::size_t width, std::size_t indent = 0,
                      std::size_t first_used = 0);

/// CLI11's formatter with: options in the groups they are declared in, positional ones too,
/// in declaration order; each option's argument named as it was declared (FILE, DIR, N, X, or
/// its words `a|b`), never CLI11's type markers (`INT:INT in [0 - 100]`, `FILE:FILE`); its
/// default, range and exclusions after its text in words ("default 3; 1..1000; not with
/// --weights"); every line at most kHelpColumns wide.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const
      override;
  std::string make_description(const CLI::App* app) const override;
  std::string make_usage(const CLI::App* app, std::string name) const override;
  std::string make_option(const CLI::Option* opt, bool is_positional) const override;
  std::string make_option_opts(const CLI::Option* opt) const override;
  std::string make_option_desc(const CLI::Option* opt) const override;
};

/// Gives `app` the HelpFormatter.
void use_help_format(CLI::App& app);

}  // namespace skinslide::cli
