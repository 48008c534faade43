#include "command_support.hpp"

#include <cstdio>

namespace nearshore::tools {

void set_example(CLI::App& command, const std::string& example) {
  command.footer("\nExample:\n  " + example + "\n\nMore: docs/commands/" + command.get_name() + ".md");
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

}  // namespace nearshore::tools
