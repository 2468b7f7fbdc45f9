// STUB, replaced by the real subcommand.
#include <cstdio>
#include "apps/cli/commands.h"
namespace lpir {
int RunDemo(int, char**) { std::fprintf(stderr, "demo: not built yet\n"); return 1; }
}  // namespace lpir
