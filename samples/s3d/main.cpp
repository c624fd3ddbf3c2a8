// s3d: the command-line tool. Each command lives in its own file (render_command.cpp, convert_command.cpp, ...)
// and implements cli::Command (cli_support.h); main parses the command line and runs the command given.
//
// Exit status: 0 on success (and for --help / --version / --list-devices); 1 on any error, which ends with one line
// "s3d: error: <message>" on stderr. `s3d` without a command prints the help and fails: there is nothing
// sensible to do by default, and a script calling a bare `s3d` is almost certainly a mistake.
#include <csignal>
#include <exception>
#include <iostream>
#include <memory>
#include <vector>

#include "cli_support.h"

int main(int argc, char** argv) {
  using namespace s3d::cli;
  // Past a file-size limit (ulimit -f) a write then fails with EFBIG, reported and rolled back like any other
  // write error, instead of the signal killing the run and leaving its staging folder.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"s3d: stereoscopic 3D from one rendered view and its depth (view synthesis), "
               "checked against a two-pass reference",
               "s3d"};
  app.set_version_flag("--version", std::string("s3d ") + S3D_VERSION, "Print the version (" S3D_VERSION ") and exit");
  bool listDevicesOnly = false;
  app.add_flag("--list-devices", listDevicesOnly, "List the Vulkan devices and whether s3d can use them, then exit");

  std::vector<std::unique_ptr<Command>> commands;
  commands.push_back(addRenderCommand(app));
  commands.push_back(addConvertCommand(app));
  commands.push_back(addBenchCommand(app));
  commands.push_back(addRegressCommand(app));
  commands.push_back(addTuneCommand(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& success) {  // --help
    return app.exit(success);
  } catch (const CLI::ParseError& error) {
    std::string command;
    for (const auto& candidate : commands)
      if (candidate->subcommand->parsed()) command = candidate->subcommand->get_name() + " ";
    return fail(std::string(error.what()) + " (see `s3d " + command + "--help`)");
  }

  try {
    if (listDevicesOnly) {
      listDevices();
      return 0;
    }
    for (const auto& command : commands)
      if (command->subcommand->parsed()) return command->run();
    std::cerr << app.help();
    std::string names;
    for (const auto& command : commands) names += (names.empty() ? "`s3d " : ", `s3d ") + command->subcommand->get_name() + "`";
    return fail("no command given (try " + names + ")");
  } catch (const std::exception& error) {
    return fail(error.what());
  } catch (...) {
    return fail("unknown exception");
  }
}
