#include "app/cli.h"

int main(int argc, char** argv) { return penumbra::runCli(argc, argv); }
