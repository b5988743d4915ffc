#include "help_format.h"

#include <algorithm>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

namespace skinslide::cli {
namespace {

// Where an option's text starts: after "  --name ARG" and a space, or on a line of its own.
constexpr std::size_t kTextColumn = 30;

// A Range's upper bound that only says "any": the largest int (a vertex id).
const std::string kNoBound = std::to_string(std::numeric_limits<int>::max());

// CLI11's names of plain types, as the help names them.
std::string our_type_name(const std::string& cli11) {
  if (cli11 == "INT" || cli11 == "UINT") return "N";
  if (cli11 == "FLOAT") return "X";
  if (cli11 == "TEXT") return "WORD";
  return cli11;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

// An option's type as CLI11 composes it: the declared name, then each check's description, all
// joined by ':' ("INT:INT in [0 - 100]", "TEXT:{elastic,paper}", "FILE:FILE").
struct TypeText {
  std::string name;   // the declared name: FILE, N, or CLI11's INT, TEXT ...
  std::string words;  // an IsMember check's words, "elastic|paper"; empty: none
  std::string range;  // a Range check's bounds, "0..100"; empty: none
};

TypeText type_text(const CLI::Option* opt) {
  std::vector<std::string> parts;
  std::istringstream in(opt->get_type_name());
  for (std::string part; std::getline(in, part, ':');) parts.push_back(part);
  TypeText t;
  if (!parts.empty()) t.name = parts.front();
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (p.size() > 2 && p.front() == '{' && p.back() == '}') {
      t.words = replaced(p.substr(1, p.size() - 2), ",", "|");
    } else if (const std::size_t open = p.find(" in ["); open != std::string::npos) {
      std::string bounds = p.substr(open + 5);
      if (!bounds.empty() && bounds.back() == ']') bounds.pop_back();
      const std::size_t dash = bounds.find(" - ");
      const std::string high = dash == std::string::npos ? "" : bounds.substr(dash + 3);
      t.range = high == kNoBound ? bounds.substr(0, dash) + " or more"
                                 : replaced(replaced(bounds, " - ", ".."), "e+0", "e");
    }
  }
  return t;
}

// A positional's name in the help: the name it was declared with (BIND, FRAME...), else its own.
std::string positional_name(const CLI::Option* opt) {
  const std::string declared = type_text(opt).name;
  return our_type_name(declared) == declared && !declared.empty() ? declared : opt->get_name(true);
}

// The options of `group`, positional or not, in declaration order (--help itself too, unless
// `mode` shows a subcommand).
std::vector<const CLI::Option*> group_options(const CLI::App* app, const std::string& group,
                                              CLI::AppFormatMode mode) {
  return app->get_options([&](const CLI::Option* opt) {
    return opt->get_group() == group &&
           (mode != CLI::AppFormatMode::Sub ||
            (opt != app->get_help_ptr() && opt != app->get_help_all_ptr()));
  });
}

}  // namespace

std::string wrap_text(const std::string& text, std::size_t width, std::size_t indent,
                      std::size_t first_used) {
  std::string out;
  std::size_t used = first_used;
  std::istringstream paragraphs(text);
  bool first_paragraph = true;
  for (std::string paragraph; std::getline(paragraphs, paragraph);) {
    if (!first_paragraph) {
      out += "\n" + std::string(indent, ' ');
      used = indent;
    }
    first_paragraph = false;
    if (starts_with(paragraph, " ")) {  // an example: as it is
      out += paragraph;
      continue;
    }
    std::istringstream words(paragraph);
    bool line_empty = true;
    for (std::string word; words >> word;) {
      if (!line_empty && used + 1 + word.size() > width) {
        out += "\n" + std::string(indent, ' ');
        used = indent;
        line_empty = true;
      }
      if (!line_empty) {
        out += ' ';
        ++used;
      }
      out += word;
      used += word.size();
      line_empty = false;
    }
  }
  return out;
}

std::string HelpFormatter::make_description(const CLI::App* app) const {
  const std::string& description = app->get_description();
  return description.empty() ? "" : wrap_text(description, kHelpColumns) + "\n";
}

std::string HelpFormatter::make_usage(const CLI::App* app, std::string name) const {
  std::string usage = "Usage: " + name + " [options]";
  for (const CLI::Option* opt : app->get_options([](const CLI::Option* o) {
         return o->get_positional();
       })) {
    const std::string shown = positional_name(opt);
    usage += " " + (opt->get_required() ? shown : "[" + shown + "]");
  }
  return wrap_text(usage, kHelpColumns, 2) + "\n";
}

std::string HelpFormatter::make_option_opts(const CLI::Option* opt) const {
  if (!opt->get_option_text().empty()) return " " + opt->get_option_text();
  if (opt->get_type_size() == 0) return "";  // a flag
  const TypeText t = type_text(opt);
  return " " + (t.words.empty() ? our_type_name(t.name) : t.words);
}

std::string HelpFormatter::make_option_desc(const CLI::Option* opt) const {
  std::vector<std::string> notes;
  const TypeText t = type_text(opt);
  if (opt->get_required()) notes.push_back("required");
  if (opt->get_type_size() != 0 && !opt->get_default_str().empty())
    notes.push_back("default " + opt->get_default_str());
  if (!t.range.empty()) notes.push_back(t.range);
  // CLI11 holds them in sets of pointers: in the order of their names, the same every run.
  const auto names_of = [](const std::set<CLI::Option*>& options) {
    std::vector<std::string> names;
    for (const CLI::Option* other : options)
      names.push_back(other->get_positional() ? positional_name(other) : other->get_name());
    std::sort(names.begin(), names.end());
    std::string text;
    for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
    return text;
  };
  if (!opt->get_excludes().empty()) notes.push_back("not with " + names_of(opt->get_excludes()));
  if (!opt->get_needs().empty()) notes.push_back("needs " + names_of(opt->get_needs()));
  std::string text = opt->get_description();
  if (notes.empty()) return text;
  text += " (";
  for (std::size_t i = 0; i < notes.size(); ++i) text += (i ? "; " : "") + notes[i];
  return text + ")";
}

std::string HelpFormatter::make_option(const CLI::Option* opt, bool is_positional) const {
  const std::string names = is_positional ? positional_name(opt)
                                          : replaced(opt->get_name(false, true), ",", ", ") +
                                                make_option_opts(opt);
  std::string line = "  " + names;
  const std::string text = make_option_desc(opt);
  if (text.empty()) return line + "\n";
  if (line.size() + 1 > kTextColumn)
    line += "\n" + std::string(kTextColumn, ' ');
  else
    line += std::string(kTextColumn - line.size(), ' ');
  return line + wrap_text(text, kHelpColumns, kTextColumn, kTextColumn) + "\n";
}

std::string HelpFormatter::make_help(const CLI::App* app, std::string name,
                                     CLI::AppFormatMode mode) const {
  std::string out = make_description(app) + "\n" + make_usage(app, name);
  for (const std::string& group : app->get_groups()) {
    const std::vector<const CLI::Option*> opts = group_options(app, group, mode);
    if (group.empty() || opts.empty()) continue;
    out += "\n" + group + ":\n";
    for (const CLI::Option* opt : opts) out += make_option(opt, opt->get_positional());
  }
  return out + "\n" + make_footer(app);
}

void use_help_format(CLI::App& app) { app.formatter(std::make_shared<HelpFormatter>()); }

}  // namespace skinslide::cli
