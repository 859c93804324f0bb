#include "app/cli/cli.h"

int main(int argc, char** argv) { return sortcell::app::RunCli(argc, argv); }
