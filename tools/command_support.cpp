#include "command_support.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <fmt/core.h>

#include "nearshore/core/error.hpp"

namespace nearshore::tools {
namespace {

bool is_identifier_character(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// "[0, 1)", "> 0", ">= 16", "any finite number".
std::string describe_range(Bound low, Bound high) {
  const bool has_low = std::isfinite(low.value), has_high = std::isfinite(high.value);
  if (has_low && has_high)
    return fmt::format("{}{:g}, {:g}{}", low.inclusive ? "[" : "(", low.value, high.value, high.inclusive ? "]" : ")");
  if (has_low) return fmt::format("{} {:g}", low.inclusive ? ">=" : ">", low.value);
  if (has_high) return fmt::format("{} {:g}", high.inclusive ? "<=" : "<", high.value);
  return "any finite number";
}

}  // namespace

Bound unbounded() { return {std::numeric_limits<double>::infinity(), false}; }

CLI::Validator number_in(Bound low, Bound high) {
  if (std::isinf(low.value)) low.value = -std::numeric_limits<double>::infinity();
  const std::string range = describe_range(low, high);
  return CLI::Validator(
      [low, high, range](std::string& text) -> std::string {
        // The whole text must be one number (strtod also reads "nan", "inf" and "1e3").
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (text.empty() || end != text.c_str() + text.size())
          return fmt::format("'{}' is not a number; allowed: {}", text, range);
        if (!std::isfinite(value)) return fmt::format("{} is not a finite number; allowed: {}", text, range);
        const bool above_low = low.inclusive ? value >= low.value : value > low.value;
        const bool below_high = high.inclusive ? value <= high.value : value < high.value;
        if (!above_low || !below_high) return fmt::format("{} is out of range: allowed {}", text, range);
        return {};
      },
      range == "any finite number" ? "finite" : range.front() == '[' || range.front() == '(' ? "in " + range : range);
}

CLI::Validator finite_number() { return number_in(unbounded(), unbounded()); }

void set_example(CLI::App& command, const std::string& example) {
  // A top-level command has its own page; a subcommand (`bench play`) is a section of its parent's
  // page, "## bench play", so the link names the section's anchor. tests/docs checks every link.
  const CLI::App* parent = command.get_parent();
  const bool top_level = parent == nullptr || parent->get_parent() == nullptr;
  const std::string page = top_level ? "docs/commands/" + command.get_name() + ".md"
                                     : "docs/commands/" + parent->get_name() + ".md#" + parent->get_name() + "-" +
                                           command.get_name();
  command.footer("\nExample:\n  " + example + "\n\nMore: " + page);
}

CLI::App* add_unbuilt_command(CLI::App& app, const std::string& name, const std::string& description,
                              const std::string& example, const std::string& tracking_issue) {
  CLI::App* command = app.add_subcommand(name, description + " (not built yet)");
  set_example(*command, example);
  command->allow_extras();
  command->callback([name, tracking_issue]() {
    std::fprintf(stderr, "nearshore %s: not built yet (%s). Nothing was computed or written.\n", name.c_str(),
                 tracking_issue.c_str());
    throw ExitStatus{3};
  });
  return command;
}

std::string name_flags(const std::string& text, const FlagTable& flags) {
  std::string named = text;
  for (const auto& [parameter, flag] : flags) {
    const std::string replacement = parameter + " (" + flag + ")";
    std::size_t at = named.find(parameter);
    while (at != std::string::npos) {
      // Whole names only: BathyRequest::sign is not the start of BathyRequest::signature.
      const std::size_t end = at + parameter.size();
      const bool whole = (at == 0 || !is_identifier_character(named[at - 1])) &&
                         (end == named.size() || !is_identifier_character(named[end]));
      if (whole) named.replace(at, parameter.size(), replacement);
      at = named.find(parameter, whole ? at + replacement.size() : end);
    }
  }
  return named;
}

std::function<void()> naming_flags_in_errors(FlagTable flags, std::function<void()> callback) {
  return [flags = std::move(flags), callback = std::move(callback)]() {
    try {
      callback();
    } catch (const Error& e) {
      throw Error(name_flags(e.subject(), flags), name_flags(e.problem(), flags), name_flags(e.fix(), flags));
    }
  };
}

}  // namespace nearshore::tools
