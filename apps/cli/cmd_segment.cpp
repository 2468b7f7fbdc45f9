// STUB, replaced by the real subcommand.
#include <cstdio>
#include "apps/cli/commands.h"
namespace lpir {
int RunSegment(int, char**) { std::fprintf(stderr, "segment: not built yet\n"); return 1; }
}  // namespace lpir
