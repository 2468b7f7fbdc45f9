// STUB, replaced by the real subcommand.
#include <cstdio>
#include "apps/cli/commands.h"
namespace lpir {
int RunEvaluate(int, char**) { std::fprintf(stderr, "evaluate: not built yet\n"); return 1; }
}  // namespace lpir
