#include "app/cli.h"

int main(int argc, char** argv) { return sortcell::app::RunCli(argc, argv); }
