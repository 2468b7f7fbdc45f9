// STUB, replaced by the real subcommand.
#include <cstdio>
#include "apps/cli/commands.h"
namespace lpir {
int RunSimulate(int, char**) { std::fprintf(stderr, "simulate: not built yet\n"); return 1; }
}  // namespace lpir
