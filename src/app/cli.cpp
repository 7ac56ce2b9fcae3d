#include "app/cli.h"

#include <cstdio>

namespace penumbra {
int runCli(int, char**) { std::fprintf(stderr, "penumbra: not built yet\n"); return 1; }
}
