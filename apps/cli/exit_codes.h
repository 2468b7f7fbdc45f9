// The exit codes of lpir-gseg, the same for every command, and their help text. A command
// returns kExitOk, kExitSomeFailed or kExitRefused itself; main (apps/cli/main.cpp) turns what a
// command throws into an exit code: RefusedError kExitRefused; std::invalid_argument (and its
// subclasses) kExitUsage, the command line asks for something wrong; any other exception
// kExitCannotRun, an error that stopped the command. So a command throws std::invalid_argument
// only for its arguments (options, names of sensors, backends, protocols), never for the
// contents of a file.
#pragma once
#include <stdexcept>

namespace lpir {

enum ExitCode : int {
  kExitOk = 0,          // done: every input
  kExitSomeFailed = 1,  // done, but inputs failed (each named on stderr); every other one written
  kExitUsage = 2,       // the command line is wrong; nothing done
  kExitRefused = 3,     // ran, but its result fails a check and is withheld
  kExitCannotRun = 4,   // an error stopped the command (named on stderr)
};

// A result that fails its check (labels that differ from the CPU reference's): exit code
// kExitRefused, the message on stderr.
class RefusedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The table, for `lpir-gseg --help` and `lpir-gseg help exit-codes`.
inline constexpr char kExitCodesHelp[] =
    "exit codes (the same for every command; the reason is always on stderr):\n"
    "  0  done: every input\n"
    "  1  done, but some inputs failed (segment: each named, every other one written;\n"
    "     evaluate: the missing predictions named, the rest scored)\n"
    "  2  usage: unknown command or option, a missing or bad value, an unknown sensor,\n"
    "     backend, protocol or --set name, an input folder without clouds, two inputs that\n"
    "     would write one output; nothing done\n"
    "  3  refused: it ran, but the result fails a check and is withheld (calibrate: the scans\n"
    "     give no trustworthy tilt, no profile written; demo, bench: Vulkan's labels differ\n"
    "     from the CPU reference's)\n"
    "  4  cannot run: an error stopped it (a file it needs is missing or unreadable, such as a\n"
    "     profile file or evaluate's labels; no usable Vulkan device where one was asked for;\n"
    "     an output that cannot be written)\n";

// The last line of every command's --help.
inline constexpr char kExitCodesLine[] =
    "exit codes: 0 done, 1 some inputs failed, 2 usage, 3 refused, 4 cannot run "
    "(lpir-gseg help exit-codes)\n";

}  // namespace lpir
