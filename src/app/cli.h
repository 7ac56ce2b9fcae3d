#pragma once

namespace penumbra {
// The `penumbra` program: parses the command line, runs the command, and turns every
// penumbra::Error into a one-line message on stderr and exit code 1.
int runCli(int argc, char** argv);
}
