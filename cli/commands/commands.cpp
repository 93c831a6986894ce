#include "commands/commands.hpp"

#include <algorithm>
#include <iostream>
#include <ostream>

namespace plyfit::cli {

std::vector<Command>& commands() {
  static std::vector<Command> list;
  return list;
}

std::string error_line(const std::string& text, const std::string& code) {
  std::string line = text + " [" + code + "]";
  std::replace(line.begin(), line.end(), '\n', ' ');
  return line;
}

std::string error_line(const Error& e, const exporters::InputNamer& name_input) {
  return error_line(exporters::describe(e, name_input), to_string(e.code));
}

void print_error(const Error& e, const exporters::InputNamer& name_input) {
  std::cerr << "plyfit: error: " << error_line(e, name_input) << "\n";
}

int error_exit(int exit_code, const Error& e, const exporters::InputNamer& name_input) {
  print_error(e, name_input);
  return exit_code;
}

void print_help(std::ostream& os, const CommandHelp& help, const OptionTable& table) {
  os << "usage: " << help.usage << "\n\n" << help.description << "\noptions:\n";
  print_options(os, table);
  if (help.more) help.more(os);
}

Arguments read_arguments(const std::vector<std::string>& args, const OptionTable& table,
                         const Operands& operands, const CommandHelp& help) {
  Arguments a;
  if (wants_help(args)) {
    print_help(std::cout, help, table);
    a.exit = kExitOk;
    return a;
  }
  auto raw = parse_command_line(args, table, operands.key);
  if (!raw) {
    a.exit = error_exit(kExitUsage, raw.error(), flag_namer(table));
    return a;
  }
  a.raw = std::move(raw).value();
  const auto found = a.raw.values.find(operands.key);
  const std::size_t n = found == a.raw.values.end() ? 0 : found->second.size();
  if (n == 0)
    a.exit = error_exit(
        kExitUsage, Error{ErrorCode::kMissingArgument,
                          "",
                          {"the " + operands.what, help.usage.substr(0, help.usage.find('\n'))}});
  else if (n > 1 && !operands.several)
    a.exit = error_exit(kExitUsage, Error{ErrorCode::kUnexpectedArgument,
                                          "",
                                          {found->second[1], "one " + operands.what + " only"}});
  return a;
}

Command options_command(std::string name, std::string summary, int order, ArgumentSpec spec,
                        std::function<int(const Options&)> run) {
  return {std::move(name), std::move(summary), order,
          [spec, run](const std::vector<std::string>& args) {
            const OptionTable& table = spec.table();
            const Arguments a = read_arguments(args, table, spec.operands, spec.help);
            if (a.exit) return *a.exit;
            return run(Options(a.raw, table));
          }};
}

CatchInterrupts::CatchInterrupts(void (*handler)(int)) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &old_int_);
  sigaction(SIGTERM, &sa, &old_term_);
}

CatchInterrupts::~CatchInterrupts() {
  sigaction(SIGINT, &old_int_, nullptr);
  sigaction(SIGTERM, &old_term_, nullptr);
}

}  // namespace plyfit::cli
