// One declaration per option, used by the command, the API, Python and Blender: its name, the
// member it sets, its range or its words and its help. The member's initialiser in its options
// struct is the default: a table reads it from a default-constructed struct and never writes it
// again. Each method declares its tunables in a table beside its options
// (elastic/elastic_options.h, paper/paper_options.h), the run its shared options
// (pipeline/run_options.h), the command its own (pipeline/command_options.h). Every client reads
// the tables: the command line declares its CLI11 options from them and refuses a method's options
// with the other method, the API checks the ranges (skinslide.h check_options) and the bind's
// set-up every option's rule (check_rules), the report lists a method's (pipeline/method.h), and
// the Python module takes them as keyword arguments and lists them (option_specs), from which the
// Blender add-on makes its properties. Adding an option is adding one entry to one table.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/error.h"
#include "core/figures.h"
#include "core/number_format.h"

namespace skinslide {

/// A number option: the member it sets and the inclusive range it takes.
template <class Options, class T>
struct NumberOption {
  T Options::*member;
  T low;
  T high;
};

/// One word a word option takes and the value it stands for.
template <class Value>
struct Word {
  const char* word;
  Value value;
};

/// The words of an enum's option: what they name (for errors: "density") and each word with its
/// value, in the order --help lists them. The first word naming a value is its name; a later one
/// is another spelling.
template <class Value, std::size_t N>
struct Words {
  const char* what;
  std::array<Word<Value>, N> words;

  /// The first word naming `value` ("?" when none does).
  std::string name(Value value) const {
    for (const Word<Value>& w : words)
      if (w.value == value) return w.word;
    return "?";
  }
  /// The value `word` names. \throw Error(Usage) "unknown <what> '<word>' (<every word>)".
  Value value(const std::string& word) const {
    std::string known;
    for (const Word<Value>& w : words) {
      if (word == w.word) return w.value;
      known += (known.empty() ? "" : ", ") + std::string(w.word);
    }
    throw Error(ErrorKind::Usage,
                "unknown " + std::string(what) + " '" + word + "' (" + known + ")");
  }
};

/// A word option: the words it takes, in the order --help lists them, and how it reads its member
/// (the first word of the member's value) and sets it (\throw Error(Usage) on another word).
template <class Options>
struct WordOption {
  std::vector<std::string> words;
  std::function<std::string(const Options&)> get;
  std::function<void(Options&, const std::string&)> set;
};

template <class Options>
using OptionValue = std::variant<NumberOption<Options, int>, NumberOption<Options, unsigned>,
                                 NumberOption<Options, double>, WordOption<Options>>;

/// One option of an options struct.
template <class Options>
struct Option {
  /// "q-floor": --q-floor on the command line and a --config file's key; api_name() elsewhere.
  std::string name;
  std::string help;  ///< the command line's help text
  OptionValue<Options> value;
  /// Also read by the run whatever the method (--lookup-size sizes the dumps' ID images too): the
  /// command line takes it with either method, where the API and Python refuse it with the other.
  bool run_wide = false;
  /// A solver's internal, not a choice a user makes: --help lists it in its Research group, the
  /// Blender add-on under Advanced (lib/*/README.md document each).
  bool research = false;
  /// Set: the option applies only when the word option `needs_option` of the same table is
  /// `needs_word` (the elastic search's internals need --solver search); the command line refuses
  /// it otherwise.
  const char* needs_option = nullptr;
  const char* needs_word = nullptr;
  /// A rule of the option's value beyond its range, often against the other options' values
  /// (--ease-in below --rotation-fits); none when null. check_rules() applies every table's.
  /// \throw Error(Usage) naming the option when `options` break it.
  void (*rule)(const Options& options) = nullptr;
};

/// The options of one options struct, in the order --help, the report and Python list them.
template <class Options>
using OptionTable = std::vector<Option<Options>>;

/// The table of an options struct, defined beside it (elastic/elastic_options.h,
/// paper/paper_options.h, pipeline/run_options.h).
template <class Options>
const OptionTable<Options>& option_table();

/// An option's name as the API, the report and Python spell it: '_' for '-' ("q_floor").
inline std::string api_name(std::string name) {
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

/// A word option setting an enum member. `words` must outlive the option (a constant at
/// namespace scope).
template <class Options, class Value, std::size_t N>
WordOption<Options> word_option(Value Options::*member, const Words<Value, N>& words) {
  WordOption<Options> option;
  for (const Word<Value>& w : words.words) option.words.push_back(w.word);
  option.get = [member, &words](const Options& o) { return words.name(o.*member); };
  option.set = [member, &words](Options& o, const std::string& word) {
    o.*member = words.value(word);
  };
  return option;
}

/// The option's value in `options` as a figure named api_name(option.name): a number, or its word.
template <class Options>
Figure option_figure(const Option<Options>& option, const Options& options) {
  const FigureValue value = std::visit(
      [&](const auto& v) -> FigureValue {
        if constexpr (requires { v.member; }) {
          using T = std::decay_t<decltype(options.*v.member)>;
          if constexpr (std::is_same_v<T, double>)
            return options.*v.member;
          else
            return static_cast<long long>(options.*v.member);
        } else {
          return v.get(options);
        }
      },
      option.value);
  return {api_name(option.name), value};
}

/// Every option's figure, in the table's order.
template <class Options>
Figures option_figures(const OptionTable<Options>& table, const Options& options) {
  Figures figures;
  for (const Option<Options>& option : table) figures.push_back(option_figure(option, options));
  return figures;
}

/// Checks every number option of `options` against its range.
/// \throw Error(Usage) "<api name> = <value> is outside [<low>, <high>]" (shortest numbers).
template <class Options>
void check_ranges(const OptionTable<Options>& table, const Options& options) {
  for (const Option<Options>& option : table)
    std::visit(
        [&](const auto& v) {
          if constexpr (requires { v.member; }) {
            const auto value = options.*v.member;
            if (!(value >= v.low && value <= v.high))  // NaN fails too
              throw Error(ErrorKind::Usage, api_name(option.name) + " = " +
                                                format_double(double(value)) + " is outside [" +
                                                format_double(double(v.low)) + ", " +
                                                format_double(double(v.high)) + "]");
          }
        },
        option.value);
}

/// Applies every option's rule (Option::rule) to `options`, in the table's order: with
/// check_ranges, every check of an options struct's values, each declared once in its entry.
/// \throw Error(Usage) as the first rule broken.
template <class Options>
void check_rules(const OptionTable<Options>& table, const Options& options) {
  for (const Option<Options>& option : table)
    if (option.rule) option.rule(options);
}

}  // namespace skinslide
